// The assembler pipeline in one place: read and parse every root file into a unit, place the
// units one after another, resolve names across them, encode, append STOP, check the target.
#include <algorithm>

#include "internal.hpp"

namespace tmcl {
namespace detail {
namespace {

struct FieldRange {
  std::int64_t min, max;
  const char* text;
};

FieldRange range_of(Field f) {
  switch (f) {
    case Field::Type:
    case Field::Motor: return {0, 255, "0 to 255"};
    case Field::Value: return {INT32_MIN, UINT32_MAX, "-2147483648 to 4294967295"};
  }
  return {0, 0, ""};
}

const char* field_name(Field f) {
  switch (f) {
    case Field::Type: return "type";
    case Field::Motor: return "motor/bank";
    case Field::Value: return "value";
  }
  return "?";
}

void put(Instruction& ins, Field f, std::int64_t v) {
  switch (f) {
    case Field::Type: ins.type = static_cast<std::uint8_t>(v); break;
    case Field::Motor: ins.motor = static_cast<std::uint8_t>(v); break;
    case Field::Value: ins.value = static_cast<std::int32_t>(static_cast<std::uint32_t>(v)); break;
  }
}

class Encoder {
 public:
  Encoder(Resolver& r, Diagnostics& d) : resolver_(r), diags_(d) {}

  // Encodes statement `s` of unit `u`; false when it could not be encoded.
  bool encode(int u, const Stmt& s, Instruction& ins) {
    if (s.count < 0) return false;
    bool ok = true;
    if (!s.op) {  // .raw
      static constexpr const char* names[] = {"opcode", "type", "motor", "value"};
      std::int64_t v[4]{};
      for (int k = 0; k < 4; ++k) {
        auto r = resolver_.eval(u, s.operands[static_cast<std::size_t>(k)].expr);
        if (!r) {
          ok = false;
          continue;
        }
        FieldRange fr = k == 3 ? range_of(Field::Value) : range_of(Field::Type);
        if (*r < fr.min || *r > fr.max) {
          diags_.error(s.operands[static_cast<std::size_t>(k)].loc, "value " + std::to_string(*r) + " does not fit the " +
                                                                        names[k] + " field (" + fr.text + ")");
          ok = false;
        }
        v[k] = *r;
      }
      if (!ok) return false;
      ins.op = static_cast<std::uint8_t>(v[0]);
      put(ins, Field::Type, v[1]);
      put(ins, Field::Motor, v[2]);
      put(ins, Field::Value, v[3]);
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
        auto r = resolver_.eval(u, o.expr);
        if (!r) {
          ok = false;
          continue;
        }
        v = *r;
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
                                  " of " + std::string(s.op->mnemonic));
      }
      put(ins, spec.field, v);
    }
    return ok;
  }

 private:
  bool unknown_name(int u, const Operand& o) { return resolver_.lookup(u, upper(resolver_.name_of(u, o.expr))).first < 0; }

  // A name in a keyword position that is neither a keyword nor a symbol: say which keywords fit.
  void unknown_keyword(int u, KwSet set, const Operand& o) {
    std::string word(resolver_.name_of(u, o.expr));
    std::vector<std::string_view> names;
    std::string list;
    for (const auto& k : all_keywords())
      if (k.set == set) {
        names.push_back(k.name);
        list += (list.empty() ? "" : ", ") + std::string(k.name);
      }
    auto& d = diags_.error(o.loc, "unknown " + std::string(kwset_name(set)) + " '" + word + "'");
    std::string hint = closest_match(word, names);
    if (!hint.empty()) diags_.note(d, o.loc, "did you mean '" + hint + "'?");
    diags_.note(d, o.loc, "expected one of " + list);
  }

  Resolver& resolver_;
  Diagnostics& diags_;
};

}  // namespace
}  // namespace detail

AsmResult assemble(const std::vector<std::string>& files, const AsmOptions& options, FileReader& reader) {
  using namespace detail;
  AsmResult out;
  out.diags.set_warnings_are_errors(options.warnings_are_errors);
  const Profile& profile = options.profile ? *options.profile : generic_profile();

  // read, lex, parse
  std::vector<Unit> units;
  std::vector<std::string> seen;
  for (const auto& file : files) {
    if (std::find(seen.begin(), seen.end(), file) != seen.end()) {
      out.diags.error(SourceLoc{}, "'" + file + "' is named twice on the command line");
      continue;
    }
    seen.push_back(file);
    units.emplace_back();
    parse_unit(file, options, reader, out.sources, out.diags, units.back());
  }

  // place the units one after another
  int base = 0;
  for (auto& u : units) {
    u.base = base;
    base += static_cast<int>(u.stmts.size());
  }

  // resolve names
  Resolver resolver(units, out.diags, out.sources);
  resolver.link_exports();
  resolver.check_redefinitions();

  // encode and check against the target
  Encoder encoder(resolver, out.diags);
  for (int u = 0; u < static_cast<int>(units.size()); ++u) {
    for (const Stmt& s : units[static_cast<std::size_t>(u)].stmts) {
      Instruction ins;
      bool ok = encoder.encode(u, s, ins);
      if (ok && s.op) check_against_profile(profile, s, ins, out.diags);
      out.program.push_back(ok ? ins : Instruction{});
      out.lines.push_back(LineInfo{s.loc.file, s.loc.line});
    }
  }

  bool appended = false;
  if (options.append_stop && (out.program.empty() || out.program.back().op != static_cast<std::uint8_t>(Op::STOP))) {
    appended = true;
    out.program.push_back(Instruction{static_cast<std::uint8_t>(Op::STOP), 0, 0, 0});
    out.lines.push_back(LineInfo{-1, 0});
  }

  // jump targets must lie inside the program
  for (const auto& u : units) {
    for (const Stmt& s : u.stmts) {
      if (!s.op || s.count < 0) continue;
      const Instruction& ins = out.program[static_cast<std::size_t>(u.base + s.address)];
      for (std::size_t k = 0; k < s.op->operands.size(); ++k) {
        if (s.op->operands[k].role != Role::Address) continue;
        auto target = static_cast<std::int64_t>(ins.value);
        if (target < 0 || target >= static_cast<std::int64_t>(out.program.size()))
          out.diags.warning(s.operands[k].loc, "address " + std::to_string(target) +
                                                   " is outside the program (addresses 0 to " +
                                                   std::to_string(out.program.size() - 1) + ")");
      }
    }
  }

  if (profile.program_memory > 0 && static_cast<int>(out.program.size()) > profile.program_memory)
    out.diags.error(SourceLoc{}, "the program needs " + std::to_string(out.program.size()) + " instructions" +
                                     (appended ? " (with the appended STOP)" : "") + " but " +
                                     std::string(profile.title) + " has room for " +
                                     std::to_string(profile.program_memory));

  for (int u = 0; u < static_cast<int>(units.size()); ++u) {
    for (int d = 0; d < static_cast<int>(units[static_cast<std::size_t>(u)].defs.size()); ++d) {
      const SymDef& def = units[static_cast<std::size_t>(u)].defs[static_cast<std::size_t>(d)];
      if (def.from_command_line) continue;
      std::int64_t value = def.kind == SymbolKind::Label ? units[static_cast<std::size_t>(u)].base + def.address
                                                         : def.state == EvalState::Done ? def.value
                                                                                        : 0;
      if (def.kind == SymbolKind::Constant && def.state == EvalState::Failed) continue;
      if (def.kind == SymbolKind::Constant && def.state != EvalState::Done) {
        auto v = resolver.eval_def(u, d);  // an unused constant is still checked
        if (!v) continue;
        value = *v;
      }
      out.symbols.push_back(Symbol{def.name, def.kind, value, def.loc, def.exported});
    }
  }
  return out;
}

}  // namespace tmcl
