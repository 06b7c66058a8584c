// Linking: reading the inputs (sources, objects, libraries), choosing library members, choosing
// the target, applying an object's relocations, and building an object from a unit (-c).
// The order of the stages is in assemble() (assembler.cpp).
#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "internal.hpp"
#include "tmcl/targets.hpp"
#include "tmcl/program_image.hpp"

namespace tmcl::detail {
namespace {

std::string text_at(const SourceSet& sources, SourceLoc loc) {
  if (loc.file < 0 || loc.col < 1) return {};
  std::string_view line = sources.files[static_cast<std::size_t>(loc.file)].line(loc.line);
  auto start = static_cast<std::size_t>(loc.col - 1);
  if (start >= line.size()) return {};
  return std::string(line.substr(start, static_cast<std::size_t>(loc.len)));
}


std::string with_addend(const std::string& name, std::int64_t k) {
  if (k == 0) return name;
  return name + (k < 0 ? " - " + std::to_string(0 - static_cast<std::uint64_t>(k)) : " + " + std::to_string(k));
}

// The keys a unit exports and imports (library member selection runs before units are resolved).
void exports_of(const ObjectFile& obj, std::vector<std::string>& out) {
  for (const auto& s : obj.symbols)
    if (s.binding == ObjBinding::Export) out.push_back(upper(s.name));
}

}  // namespace

void object_unit(const ObjectFile& obj, const std::string& input_name, SourceSet& sources, Unit& unit) {
  unit.object = &obj;
  unit.input_name = input_name;
  unit.no_append_stop = (obj.flags & kObjNoAppendStop) != 0;
  for (const auto& f : obj.files) {
    SourceFile sf;
    sf.name = f;
    sf.path = "<object " + input_name + ">";
    unit.object_files.push_back(sources.add(std::move(sf)));
  }
  for (std::size_t i = 0; i < obj.symbols.size(); ++i) {
    const ObjSymbol& s = obj.symbols[i];
    std::string key = upper(s.name);
    SourceLoc loc = unit.object_loc(s.file, s.line);
    if (s.binding == ObjBinding::Import) {
      if (unit.imports.emplace(key, loc).second) {
        unit.import_index.emplace(key, static_cast<int>(unit.import_order.size()));
        unit.import_order.push_back(key);
      }
      continue;
    }
    SymDef d;
    d.name = s.name;
    d.kind = s.kind == ObjSymKind::Label ? SymbolKind::Label : SymbolKind::Constant;
    d.loc = loc;
    d.obj_symbol = static_cast<int>(i);
    if (d.kind == SymbolKind::Label) d.address = static_cast<int>(s.value);
    if (s.binding == ObjBinding::Export) unit.exports.emplace_back(s.name, loc);
    unit.add_def(std::move(d));  // read_object refuses an object that names a symbol twice
  }
}

void read_inputs(const std::vector<std::string>& files, const AsmOptions& options, FileReader& reader,
                 AsmResult& out, Storage& store, std::vector<InputSlot>& slots, std::string* first) {
  std::vector<std::string> seen;
  for (const auto& file : files) {
    if (std::find(seen.begin(), seen.end(), file) != seen.end()) {
      out.diags.error(SourceLoc{}, "'" + file + "' is named twice on the command line");
      continue;
    }
    seen.push_back(file);
    std::string text;
    if (first && &file == &files.front()) {
      text = std::move(*first);
    } else if (!reader.read(file, text)) {
      out.diags.error(SourceLoc{}, "cannot read '" + file + "': " + reader.last_error());
      continue;
    }
    std::string shown = file == "-" ? "<stdin>" : file;
    InputSlot slot;
    slot.name = shown;
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
    std::string error;
    switch (sniff_file(text)) {
      case FileKind::Source:
        // Binary bytes given as source: one error saying what they look like, not hundreds of
        // "unexpected character" (program_image.hpp).
        if (const std::string what = describe_binary(text); !what.empty()) {
          const std::string arg = file == "-" ? "FILE" : file;
          out.diags.error(SourceLoc{}, "'" + shown + "' is not TMCL source: it looks like " + what +
                                           "; to disassemble it: tmclasm -d " + arg + "; to run it: tmclrun " + arg);
          continue;
        }
        slot.units.emplace_back();
        parse_unit(file, options, reader, out.sources, out.diags, slot.units.back(), &text);
        break;
      case FileKind::Object:
        if (!read_object(bytes, text.size(), store.objects.emplace_back(), error)) {
          out.diags.error(SourceLoc{}, "'" + shown + "' is not a valid object: " + error);
          continue;
        }
        slot.units.emplace_back();
        object_unit(store.objects.back(), shown, out.sources, slot.units.back());
        break;
      case FileKind::Library:
        slot.library = &store.libraries.emplace_back();
        if (!read_library(bytes, text.size(), store.libraries.back(), error)) {
          out.diags.error(SourceLoc{}, "'" + shown + "' is not a valid library: " + error);
          continue;
        }
        break;
    }
    if (options.relocatable && (slot.library || (!slot.units.empty() && slot.units[0].object))) {
      out.diags.error(SourceLoc{}, "-c assembles a source file into an object; '" + shown + "' is already " +
                                       (slot.library ? "a library" : "an object"));
      continue;
    }
    slots.push_back(std::move(slot));
  }
}

// Links only the library members that export a name some linked unit imports and nobody else
// exports; repeats until nothing changes, since a member may import names of its own. Members
// are scanned library by library, member by member, so when two export the same name the first
// one wins.
void choose_members(std::vector<InputSlot>& slots, SourceSet& sources) {
  std::set<std::string> defined, wanted;
  auto add_unit = [&](const Unit& u) {
    for (const auto& [name, loc] : u.exports) defined.insert(upper(name));
    for (const auto& key : u.import_order) wanted.insert(key);
  };
  for (const auto& slot : slots)
    for (const auto& u : slot.units) add_unit(u);
  for (auto& slot : slots)
    if (slot.library) slot.chosen.assign(slot.library->members.size(), std::string());
  bool changed = true;
  while (changed) {
    changed = false;
    for (auto& slot : slots) {
      if (!slot.library) continue;
      for (std::size_t m = 0; m < slot.library->members.size(); ++m) {
        if (!slot.chosen[m].empty()) continue;
        const ObjectFile& obj = slot.library->members[m].object;
        std::vector<std::string> ex;
        exports_of(obj, ex);
        for (const auto& s : obj.symbols) {
          if (s.binding != ObjBinding::Export) continue;
          std::string key = upper(s.name);
          if (wanted.count(key) && !defined.count(key)) {
            slot.chosen[m] = s.name;
            break;
          }
        }
        if (slot.chosen[m].empty()) continue;
        changed = true;
        for (const auto& key : ex) defined.insert(key);
        for (const auto& s : obj.symbols)
          if (s.binding == ObjBinding::Import) wanted.insert(upper(s.name));
      }
    }
  }
  for (auto& slot : slots) {
    if (!slot.library) continue;
    for (std::size_t m = 0; m < slot.library->members.size(); ++m) {
      std::string name = slot.name + "(" + slot.library->members[m].name + ")";
      if (slot.chosen[m].empty()) {
        slot.unused.push_back(name);
        continue;
      }
      slot.units.emplace_back();
      object_unit(slot.library->members[m].object, name, sources, slot.units.back());
      slot.reasons.push_back(slot.chosen[m]);
    }
  }
}

// -t when given; otherwise the target the objects were built for and the sources name on their
// first line (`// tmcl-target: NAME`, targets.hpp). An object built for `generic` links into a
// program for any target (and is checked against it); inputs built for two different modules, or
// objects built for another module than -t, do not link. Targets are the same when their names
// are: a user's profile file and an object that recorded its name meet by name.
const Profile& choose_target(const AsmOptions& options, const std::vector<Unit>& units, const SourceSet& sources,
                             Diagnostics& diags) {
  const Profile* chosen = options.profile;
  std::string chosen_from;
  for (const auto& u : units) {
    std::string t;
    SourceLoc at{};
    if (u.object) {
      t = u.object->target;
    } else if (!options.profile && u.root_file >= 0 && static_cast<std::size_t>(u.root_file) < sources.files.size()) {
      auto c = target_comment(sources.files[static_cast<std::size_t>(u.root_file)].line(1));
      if (!c) continue;
      t = c->name;
      at = SourceLoc{u.root_file, 1, c->col, static_cast<int>(c->name.size())};
    } else {
      continue;
    }
    const Profile* p = nullptr;
    if (u.object) {
      p = resolve_target(t).profile;
      if (!p) {
        diags.error(SourceLoc{}, "'" + u.input_name + "' was built for the unknown target '" + t + "'");
        continue;
      }
    } else {
      TargetResult r = resolve_target(t);
      if (!r.profile) {
        diags.error(at, "the first line names a target that cannot be used: " + r.message(1));
        continue;
      }
      p = r.profile;
    }
    if (p->name == "generic") continue;
    const char* built = u.object ? " was built for " : " names the target ";
    if (options.profile) {
      if (p->name != options.profile->name)
        diags.error(SourceLoc{}, "'" + u.input_name + "'" + built + t + " but the program is linked for " +
                                     std::string(options.profile->name) + " (-t); rebuild it with -t " +
                                     std::string(options.profile->name));
      continue;
    }
    if (!chosen || chosen->name == "generic") {
      chosen = p;
      chosen_from = u.input_name;
    } else if (p->name != chosen->name) {
      diags.error(u.object ? SourceLoc{} : at, "inputs built for different targets: '" + chosen_from + "' for " +
                                                    std::string(chosen->name) + ", '" + u.input_name + "' for " + t);
    }
  }
  return chosen ? *chosen : generic_profile();
}

void link_object(Resolver& resolver, int u, const Unit& unit, const Profile& profile, AsmResult& out) {
  const ObjectFile& obj = *unit.object;
  // An object checked against another module (or none) is checked against this one now; one
  // checked against this module already needs only its relocated instructions checked again.
  bool check_all = obj.target != profile.name;
  std::size_t r = 0;
  for (std::size_t i = 0; i < obj.code.size(); ++i) {
    Instruction ins = obj.code[i];
    SourceLoc at = unit.object_loc(obj.lines[i].file, obj.lines[i].line);
    const OpInfo* info = (obj.code_flags[i] & kInsRaw) ? nullptr : op_info(ins.op);
    if (info && (info->control || info->mnemonic.empty())) info = nullptr;
    bool ok = true, recheck = false, negative = false;  // negative: a relocated value below 0
    for (; r < obj.relocs.size() && obj.relocs[r].index == i; ++r) {
      const ObjReloc& x = obj.relocs[r];
      std::int64_t v = x.addend;
      std::string what = "base";
      if (x.term == ObjTerm::Base) {
        v = static_cast<std::int64_t>(static_cast<std::uint64_t>(v) + static_cast<std::uint64_t>(unit.base));
        what = "the object's base address";
      } else {
        const std::string& name = obj.symbols[x.symbol].name;
        what = "'" + with_addend(name, x.addend) + "'";
        auto [su, sd] = resolver.lookup(u, upper(name));
        auto sym = su >= 0 ? resolver.eval_def(su, sd) : std::nullopt;
        if (!sym) {
          ok = false;  // reported as an undefined import (or at the symbol's definition)
          continue;
        }
        v = static_cast<std::int64_t>(static_cast<std::uint64_t>(v) + static_cast<std::uint64_t>(sym->k));
      }
      FieldRange fr = range_of(x.field);
      if (v < fr.min || v > fr.max) {
        out.diags.error(at, "value " + std::to_string(v) + " of " + what + " does not fit the " + field_name(x.field) +
                                " field (" + fr.text + ")");
        ok = false;
        continue;
      }
      put_field(ins, x.field, v);
      if (x.field == Field::Value) negative = v < 0;
      bool address = false;
      if (info)
        for (const auto& spec : info->operands)
          if (spec.field == x.field && spec.role == Role::Address) address = true;
      if (!address) recheck = true;
    }
    out.program.push_back(ok ? ins : Instruction{});
    out.lines.push_back(LineInfo{at.file, at.line});
    if (ok && info && (check_all || recheck)) {
      Stmt s;
      s.op = info;
      s.loc = at;
      s.count = static_cast<int>(info->operands.size());
      for (auto& o : s.operands) o.loc = at;
      check_against_profile(profile, s, ins, out.diags, negative);
    }
  }
}

ObjectFile build_object(const Unit& unit, Resolver& resolver, const AsmResult& out, const std::vector<ObjReloc>& relocs,
                        const std::vector<std::uint8_t>& flags, const Profile& profile) {
  ObjectFile obj;
  obj.target = std::string(profile.name);
  obj.flags = unit.no_append_stop ? kObjNoAppendStop : 0;
  // The file table: every file an instruction, definition or import comes from, in load order.
  std::set<int> used;
  for (const auto& l : out.lines)
    if (l.file >= 0) used.insert(l.file);
  for (const auto& d : unit.defs)
    if (!d.from_command_line && d.loc.file >= 0) used.insert(d.loc.file);
  for (const auto& [key, loc] : unit.imports)
    if (loc.file >= 0) used.insert(loc.file);
  std::map<int, std::uint32_t> file_index;
  for (int f : used) {
    file_index[f] = static_cast<std::uint32_t>(obj.files.size());
    obj.files.push_back(out.sources.files[static_cast<std::size_t>(f)].name);
  }
  auto where = [&](SourceLoc loc, ObjSymbol& s) {
    auto it = file_index.find(loc.file);
    s.file = it == file_index.end() ? kNoIndex : it->second;
    s.line = static_cast<std::uint32_t>(loc.line);
  };
  obj.code = out.program;
  obj.code_flags = flags;
  for (const auto& l : out.lines) {
    auto it = file_index.find(l.file);
    obj.lines.push_back(ObjLine{it == file_index.end() ? kNoIndex : it->second, static_cast<std::uint32_t>(l.line)});
  }
  // Definitions first, then imports; a value relative to an import refers to its symbol index.
  std::vector<std::pair<int, Value>> kept;
  for (int d = 0; d < static_cast<int>(unit.defs.size()); ++d) {
    const SymDef& def = unit.defs[static_cast<std::size_t>(d)];
    if (def.from_command_line) continue;
    if (def.kind == SymbolKind::Label) {
      kept.emplace_back(d, Value{def.address, kBaseTerm});
      continue;
    }
    if (def.state == EvalState::Failed) continue;
    auto v = def.state == EvalState::Done ? std::optional<Value>(Value{def.value, def.term}) : resolver.eval_def(0, d);
    if (v) kept.emplace_back(d, *v);
  }
  auto import_symbol = [&](int term) { return static_cast<std::uint32_t>(kept.size() + static_cast<std::size_t>(term)); };
  for (const auto& [d, v] : kept) {
    const SymDef& def = unit.defs[static_cast<std::size_t>(d)];
    ObjSymbol s;
    s.name = def.name;
    s.kind = def.kind == SymbolKind::Label ? ObjSymKind::Label : ObjSymKind::Constant;
    s.binding = def.exported ? ObjBinding::Export : ObjBinding::Local;
    s.value = v.k;
    s.term = v.term == kAbsolute ? ObjTerm::Absolute : v.term == kBaseTerm ? ObjTerm::Base : ObjTerm::Symbol;
    if (s.term == ObjTerm::Symbol) s.term_symbol = import_symbol(v.term);
    where(def.loc, s);
    obj.symbols.push_back(std::move(s));
  }
  for (const auto& key : unit.import_order) {
    ObjSymbol s;
    SourceLoc loc = unit.imports.at(key);
    s.name = text_at(out.sources, loc);
    if (s.name.empty()) s.name = key;
    s.binding = ObjBinding::Import;
    where(loc, s);
    obj.symbols.push_back(std::move(s));
  }
  for (ObjReloc r : relocs) {
    if (r.term == ObjTerm::Symbol) r.symbol = import_symbol(static_cast<int>(r.symbol));
    obj.relocs.push_back(r);
  }
  std::sort(obj.relocs.begin(), obj.relocs.end(), [](const ObjReloc& a, const ObjReloc& b) {
    return std::make_pair(a.index, static_cast<int>(a.field)) < std::make_pair(b.index, static_cast<int>(b.field));
  });
  return obj;
}

}  // namespace tmcl::detail

namespace tmcl {

LibraryResult make_library(const std::vector<std::string>& files, const AsmOptions& options, FileReader& reader) {
  LibraryResult out;
  std::set<std::string> names;
  auto add = [&](LibraryMember m, const std::string& from) {
    if (!names.insert(m.name).second) {
      out.messages += "tmclasm: error: two library members are named '" + m.name + "' (the second from '" + from +
                      "'); rename one of the files\n";
      ++out.errors;
      return;
    }
    out.library.members.push_back(std::move(m));
  };
  bool folders_said = false;
  for (const auto& file : files) {
    std::string text;
    if (!reader.read(file, text)) {
      out.messages += "tmclasm: error: cannot read '" + file + "': " + reader.last_error() + "\n";
      ++out.errors;
      continue;
    }
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
    std::string error, base = std::filesystem::path(file).filename().string();
    switch (sniff_file(text)) {
      case FileKind::Object: {
        LibraryMember m;
        m.name = base;
        if (!read_object(bytes, text.size(), m.object, error)) {
          out.messages += "tmclasm: error: '" + file + "' is not a valid object: " + error + "\n";
          ++out.errors;
          continue;
        }
        add(std::move(m), file);
        break;
      }
      case FileKind::Library: {
        Library lib;
        if (!read_library(bytes, text.size(), lib, error)) {
          out.messages += "tmclasm: error: '" + file + "' is not a valid library: " + error + "\n";
          ++out.errors;
          continue;
        }
        for (auto& m : lib.members) add(std::move(m), file);
        break;
      }
      case FileKind::Source: {
        // The root is read already (standard input cannot be read twice); includes are not. An
        // -I folder that cannot be searched is said with the first source, not with each.
        class Preloaded final : public FileOverlay {
         public:
          Preloaded(const std::string& p, std::string t, FileReader& below, bool folders)
              : FileOverlay(below), path_(p), text_(std::move(t)), folders_(folders) {}
          std::string folder_problem(const std::string& path) override {
            return folders_ ? FileOverlay::folder_problem(path) : std::string();
          }

         private:
          bool serve(const std::string& path, std::string& out) override {
            if (path != path_) return false;
            out = text_;
            return true;
          }
          std::string path_, text_;
          bool folders_;
        } preloaded(file, std::move(text), reader, !folders_said);
        folders_said = true;
        AsmOptions o = options;
        o.relocatable = true;
        AsmResult r = assemble({file}, o, preloaded);
        out.messages += r.diags.render(r.sources, options.error_limit);
        out.errors += r.diags.error_count();
        out.warnings += r.diags.warning_count();
        if (!r.ok() || !r.object) continue;
        LibraryMember m;
        m.name = file == "-" ? "stdin.o" : std::filesystem::path(base).replace_extension(".o").string();
        m.object = std::move(*r.object);
        add(std::move(m), file);
        break;
      }
    }
  }
  return out;
}

}  // namespace tmcl
