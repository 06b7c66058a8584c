// The assembler pipeline in one place: read the inputs (sources into units, objects, libraries),
// choose library members, place the units one after another, choose the target, resolve names
// across units, encode sources and relocate objects, append STOP, check the target; with -c,
// build the object instead of a program.
#include <algorithm>

#include "finish.hpp"
#include "internal.hpp"

namespace tmcl {
namespace detail {
namespace {

class Encoder {
 public:
  Encoder(Resolver& r, Diagnostics& d) : resolver_(r), diags_(d) {}

  // Encodes statement `s` of unit `u`; false when it could not be encoded. In an object (-c) an
  // operand that depends on the unit's base or an import becomes a relocation in `relocs` and
  // its field stays 0; its range is checked when linking.
  bool encode(int u, const Stmt& s, Instruction& ins, std::vector<ObjReloc>& relocs) {
    negative_value_ = false;
    if (s.count < 0) return false;
    bool ok = true;
    if (!s.op) {  // .raw
      static constexpr const char* names[] = {"opcode", "type", "motor", "value"};
      static constexpr Field fields[] = {Field::Type, Field::Type, Field::Motor, Field::Value};
      std::int64_t v[4]{};
      for (int k = 0; k < 4; ++k) {
        const Operand& o = s.operands[static_cast<std::size_t>(k)];
        std::optional<Value> r;
        if (k == 0) {
          auto n = resolver_.eval(u, o.expr);
          if (n) r = Value{*n, kAbsolute};
        } else {
          r = resolver_.eval_value(u, o.expr, o.loc);
        }
        if (!r) {
          ok = false;
          continue;
        }
        if (r->term != kAbsolute) {
          relocs.push_back(reloc(s, fields[k], *r));
          continue;
        }
        FieldRange fr = k == 3 ? range_of(Field::Value) : range_of(Field::Type);
        if (r->k < fr.min || r->k > fr.max) {
          diags_.error(o.loc, "value " + std::to_string(r->k) + " does not fit the " + names[k] + " field (" +
                                  fr.text + ")");
          ok = false;
        }
        v[k] = r->k;
      }
      if (!ok) return false;
      ins.op = static_cast<std::uint8_t>(v[0]);
      put_field(ins, Field::Type, v[1]);
      put_field(ins, Field::Motor, v[2]);
      put_field(ins, Field::Value, v[3]);
      return true;
    }
    ins = Instruction{};
    ins.op = s.op->code;
    for (std::size_t k = 0; k < s.op->operands.size(); ++k) {
      const OperandSpec& spec = s.op->operands[k];
      const Operand& o = s.operands[k];
      std::int64_t v;
      if (o.expr < 0) {
        v = o.keyword;
      } else if (spec.keywords != KwSet::None && o.lone_symbol && unknown_name(u, o)) {
        unknown_keyword(u, spec.keywords, o);
        ok = false;
        continue;
      } else {
        auto r = resolver_.eval_value(u, o.expr, o.loc);
        if (!r) {
          ok = false;
          continue;
        }
        if (r->term != kAbsolute) {
          relocs.push_back(reloc(s, spec.field, *r));
          continue;
        }
        v = r->k;
      }
      FieldRange fr = range_of(spec.field);
      if (v < fr.min || v > fr.max) {
        std::string what = spec.keywords != KwSet::None ? std::string(kwset_name(spec.keywords))
                                                        : std::string(role_name(spec.role));
        diags_.error(o.loc, "value " + std::to_string(v) + " does not fit the " + field_name(spec.field) + " field (" +
                                fr.text + ") as the " + what + " of " + std::string(s.op->mnemonic));
        ok = false;
        continue;
      }
      if (spec.keywords != KwSet::None && o.expr >= 0 && !keyword_name(spec.keywords, static_cast<std::uint8_t>(v))) {
        diags_.warning(o.loc, std::to_string(v) + " is not a valid " + std::string(kwset_name(spec.keywords)) +
                                  " of " + std::string(s.op->mnemonic), "keyword-value");
      }
      put_field(ins, spec.field, v);
      if (spec.field == Field::Value) negative_value_ = v < 0;
    }
    return ok;
  }
  // Whether the last statement encoded wrote a negative number into its value field.
  bool negative_value() const { return negative_value_; }

 private:
  static ObjReloc reloc(const Stmt& s, Field f, Value v) {
    ObjReloc r;
    r.index = static_cast<std::uint32_t>(s.address);
    r.field = f;
    r.term = v.term == kBaseTerm ? ObjTerm::Base : ObjTerm::Symbol;
    r.symbol = v.term == kBaseTerm ? kNoIndex : static_cast<std::uint32_t>(v.term);  // import index for now
    r.addend = v.k;
    return r;
  }

  bool unknown_name(int u, const Operand& o) { return !resolver_.known(u, upper(resolver_.name_of(u, o.expr))); }

  // A name in a keyword position that is neither a keyword nor a symbol: say which keywords fit.
  // With an #include of the unit missing, a word with no near miss may be a constant the file
  // defines: named in that error's note instead (Resolver::excuse_undefined).
  void unknown_keyword(int u, KwSet set, const Operand& o) {
    std::string word(resolver_.name_of(u, o.expr));
    std::vector<std::string_view> names;
    std::string list;
    for (const auto& k : all_keywords())
      if (k.set == set) {
        names.push_back(k.name);
        list += (list.empty() ? "" : ", ") + std::string(k.name);
      }
    std::string hint = closest_match(word, names);
    if (hint.empty() && resolver_.closest_def(u, word).empty() && resolver_.excuse_undefined(u, word)) return;
    auto& d = diags_.error(o.loc, "unknown " + std::string(kwset_name(set)) + " '" + word + "'");
    diags_.suggest(d, o.loc, word, hint);
    diags_.note(d, o.loc, "expected one of " + list);
  }

  Resolver& resolver_;
  Diagnostics& diags_;
  bool negative_value_ = false;
};

}  // namespace
}  // namespace detail

AsmResult assemble(const std::vector<std::string>& files, const AsmOptions& options, FileReader& reader) {
  using namespace detail;
  AsmResult out;
  out.diags.set_warning_options(options.warnings);
  if (options.warnings_are_errors) out.diags.set_warnings_are_errors(true);
  const bool reloc = options.relocatable;
  if (reloc && files.size() != 1) {
    out.diags.error(SourceLoc{}, "-c assembles one source file into one object at a time");
    return out;
  }

  // An -I folder that cannot be searched is most likely a typo: said once, up front (and the
  // fast path, which reports nothing, is not taken).
  bool folder_warned = false;
  for (const auto& dir : options.include_dirs)
    if (std::string why = reader.folder_problem(dir); !why.empty()) {
      out.diags.warning(SourceLoc{}, "include folder '" + dir + "' (-I) " + why);
      folder_warned = true;
    }

  // one well-formed source: the fast path, unless it gives up (fast_path.cpp)
  std::string first;
  bool preread = false;
  if (options.fast_path && files.size() == 1 && !reloc && !folder_warned) {
    preread = reader.read(files[0], first);
    if (preread && sniff_file(first) == FileKind::Source) {
      AsmResult fast;
      fast.diags.set_warning_options(out.diags.warning_options());
      if (fast_assemble(files[0], options, reader, first, fast)) return fast;
    }
  }

  // read: parse sources into units, read objects and libraries
  Storage store;
  std::vector<InputSlot> slots;
  read_inputs(files, options, reader, out, store, slots, preread ? &first : nullptr);

  // link only the library members that resolve an import
  choose_members(slots, out.sources);

  // place the units one after another, in command-line order
  std::vector<Unit> units;
  int base = 0;
  for (auto& slot : slots) {
    for (std::size_t k = 0; k < slot.units.size(); ++k) {
      Unit& u = units.emplace_back(std::move(slot.units[k]));
      u.base = base;
      base += u.size();
      out.inputs.push_back(LinkedInput{u.input_name, u.base, u.size(), slot.library ? slot.reasons[k] : ""});
    }
    out.unused_members.insert(out.unused_members.end(), slot.unused.begin(), slot.unused.end());
  }
  const Profile& profile = choose_target(options, units, out.sources, out.diags);
  out.profile = &profile;

  // resolve names
  Resolver resolver(units, out.diags, out.sources, reloc);
  resolver.link_exports();
  resolver.check_redefinitions();

  // encode sources, relocate objects, check against the target
  Encoder encoder(resolver, out.diags);
  std::vector<ObjReloc> relocs;
  std::vector<std::uint8_t> raw_flags;
  for (int u = 0; u < static_cast<int>(units.size()); ++u) {
    const Unit& unit = units[static_cast<std::size_t>(u)];
    if (unit.object) {
      link_object(resolver, u, unit, profile, out);
      continue;
    }
    for (const Stmt& s : unit.stmts) {
      Instruction ins;
      std::size_t before = relocs.size();
      bool ok = encoder.encode(u, s, ins, relocs);
      // An operand completed at link time is checked against the target there.
      bool relocated_operand = false;
      for (std::size_t r = before; r < relocs.size(); ++r)
        if (s.op)
          for (const auto& spec : s.op->operands)
            if (spec.field == relocs[r].field && spec.role != Role::Address) relocated_operand = true;
      if (ok && s.op && !relocated_operand) check_against_profile(profile, s, ins, out.diags, encoder.negative_value());
      out.program.push_back(ok ? ins : Instruction{});
      out.lines.push_back(LineInfo{s.loc.file, s.loc.line});
      raw_flags.push_back(s.op ? 0 : kInsRaw);
    }
  }

  resolver.note_excused();

  // A program without a single instruction is almost always a mistake (the wrong file, one still
  // to be written): it assembles, to a lone STOP, but says so.
  if (!reloc && out.program.empty() && !out.diags.has_errors()) {
    SourceLoc at;
    if (!out.sources.files.empty()) at = SourceLoc{0, 1, 0, 1};
    out.diags.warning(at, options.append_stop ? "the program has no instructions; it assembles to a single STOP"
                                              : "the program has no instructions");
  }
  bool appended = false;
  bool append = options.append_stop && !reloc &&
                std::none_of(units.begin(), units.end(), [](const Unit& u) { return u.no_append_stop; });
  if (append) appended = append_stop(out.program, out.lines);  // finish.hpp, as the fast path does
  out.appended_stop = appended;

  // jump targets must lie inside the program (known only once it is linked)
  auto check_target = [&](const Instruction& ins, SourceLoc at) {
    auto target = static_cast<std::int64_t>(ins.value);
    if (outside_program(target, out.program.size()))
      out.diags.warning(at, outside_program_message(target, out.program.size()), "address");
  };
  for (const auto& u : units) {
    if (reloc) break;
    if (u.object) {
      const ObjectFile& obj = *u.object;
      for (std::size_t i = 0; i < obj.code.size(); ++i) {
        const OpInfo* info = (obj.code_flags[i] & kInsRaw) ? nullptr : op_info(obj.code[i].op);
        if (!info || info->control) continue;
        for (const auto& spec : info->operands)
          if (spec.role == Role::Address)
            check_target(out.program[static_cast<std::size_t>(u.base) + i],
                         u.object_loc(obj.lines[i].file, obj.lines[i].line));
      }
      continue;
    }
    for (const Stmt& s : u.stmts) {
      if (!s.op || s.count < 0) continue;
      for (std::size_t k = 0; k < s.op->operands.size(); ++k)
        if (s.op->operands[k].role == Role::Address)
          check_target(out.program[static_cast<std::size_t>(u.base + s.address)], s.operands[k].loc);
    }
  }

  if (exceeds_memory(profile, out.program.size()))
    out.diags.error(SourceLoc{}, exceeds_memory_message(profile, out.program.size(), appended, reloc));

  if (options.symbols) {
    std::size_t defined = 0;
    for (const Unit& unit : units) defined += unit.defs.size();
    out.symbols.reserve(defined);
  }
  for (int u = 0; u < static_cast<int>(units.size()); ++u) {
    for (int d = 0; d < static_cast<int>(units[static_cast<std::size_t>(u)].defs.size()); ++d) {
      const SymDef& def = units[static_cast<std::size_t>(u)].defs[static_cast<std::size_t>(d)];
      if (def.from_command_line) continue;
      if (def.kind == SymbolKind::Constant && def.state == EvalState::Failed) continue;
      auto v = resolver.eval_def(u, d);  // an unused constant is still checked
      if (!v || !options.symbols) continue;
      out.symbols.push_back(Symbol{def.name, def.kind, v->k, def.loc, def.exported});
    }
  }
  if (reloc && !units.empty() && !out.diags.has_errors())
    out.object = build_object(units[0], resolver, out, relocs, raw_flags, profile);
  return out;
}

}  // namespace tmcl
