// Checks an encoded instruction against a module profile. A command the module lacks is an
// error (the module would answer "invalid command"); everything the module would accept but
// probably not as meant — an unknown parameter, a write to a read-only one, a store or restore of
// one the EEPROM does not keep, a value outside the documented range, a motor, variable or I/O port that does not exist — is a warning.
#include "internal.hpp"
#include "tmcl/param_names.hpp"
#include "tmcl/params.hpp"

namespace tmcl::detail {
namespace {

SourceLoc operand_loc(const Stmt& s, Field f) {
  for (std::size_t k = 0; k < s.op->operands.size(); ++k)
    if (s.op->operands[k].field == f) return s.operands[k].loc;
  return s.loc;
}

bool has_role(const OpInfo& op, Role r) {
  for (const auto& o : op.operands)
    if (o.role == r) return true;
  return false;
}

bool writes(Op op) {
  switch (op) {
    case Op::SAP: case Op::AAP: case Op::SAPX: case Op::AAPX: case Op::SGP: case Op::AGP: return true;
    default: return false;
  }
}

bool writes_immediate(Op op) { return op == Op::SAP || op == Op::SAPX || op == Op::SGP; }

class Checker {
 public:
  Checker(const Profile& p, const Stmt& s, const Instruction& ins, Diagnostics& d, bool negative)
      : p_(p), s_(s), ins_(ins), d_(d), negative_(negative) {}

  void run() {
    if (!p_.has_command(ins_.op)) {
      d_.error(s_.loc, std::string(s_.op->mnemonic) + " is not available on " + std::string(p_.title));
      return;
    }
    Op op = static_cast<Op>(ins_.op);
    // Generic accepts every number and checks no access, but a value outside the range its
    // tables give is refused by the VM and the debugger too, so it is said here as well.
    if (p_.any_parameter) return generic_ranges(op);
    if ((op == Op::MVP || op == Op::MVPA) && ins_.type == kw::Move::COORD && !move_coord(op)) return;
    const OpInfo& info = *s_.op;
    bool coord_op = has_role(info, Role::Coord);
    if (has_role(info, Role::Motor) && ins_.motor >= p_.motors && !(coord_op && ins_.motor == 255))
      d_.warning(operand_loc(s_, Field::Motor), "motor " + std::to_string(ins_.motor) + " does not exist on " +
                                                    std::string(p_.title) +
                                                    (p_.motors == 1 ? std::string(" (it has motor 0 only)")
                                                                    : " (motors 0 to " + std::to_string(p_.motors - 1) + ")"), "target");
    if (has_role(info, Role::AxisParam)) axis(op);
    if (has_role(info, Role::GlobalParam)) global(op);
    for (const auto& spec : info.operands) {
      int v = spec.field == Field::Type ? ins_.type : spec.field == Field::Motor ? ins_.motor : 0;
      if (spec.role == Role::Var && v >= p_.user_vars)
        d_.warning(operand_loc(s_, spec.field), "user variable " + std::to_string(v) + " does not exist on " +
                                                    std::string(p_.title) + " (0 to " +
                                                    std::to_string(p_.user_vars - 1) + ")", "target");
      if (spec.role == Role::Coord && v >= p_.coords)
        d_.warning(operand_loc(s_, spec.field), "coordinate " + std::to_string(v) + " does not exist on " +
                                                    std::string(p_.title) +
                                                    (p_.coords > 0 ? " (0 to " + std::to_string(p_.coords - 1) + ")"
                                                                   : std::string(" (it has no coordinates)")), "target");
      if (spec.role == Role::Interrupt && !p_.vector(v) && !(v == 255 && op != Op::VECT))
        d_.warning(operand_loc(s_, spec.field),
                   "interrupt " + std::to_string(v) + " does not exist on " + std::string(p_.title), "target");
    }
    if (op == Op::GIO || op == Op::SIO) port(op == Op::SIO);
    velocity(op);
  }

 private:
  // MVP COORD (errata M32): a module without coordinates has no COORD type and answers "wrong
  // type", as for a command it lacks (an error; false); a coordinate it lacks is a warning.
  bool move_coord(Op op) {
    if (p_.coords == 0) {
      d_.error(operand_loc(s_, Field::Type), std::string(s_.op->mnemonic) + " COORD is not available on " + std::string(p_.title) +
                                                 " (it has no coordinates; its MVP takes ABS and REL)");
      return false;
    }
    if (op == Op::MVP && (ins_.value < 0 || ins_.value >= p_.coords))
      d_.warning(operand_loc(s_, Field::Value), "coordinate " + std::to_string(ins_.value) + " does not exist on " +
                                                    std::string(p_.title) + " (0 to " + std::to_string(p_.coords - 1) + ")",
                 "target");
    return true;
  }

  // GIO/SIO of a port the profile does not list (errata E53): the module answers "wrong type" and
  // the VM warns no-such-port; say it here with the ports of that bank there are. `ports any`
  // (generic, USB-2-SD) checks nothing; a bank outside 0 … 2 is not a port question.
  void port(bool write) {
    const int bank = ins_.motor;
    if (p_.any_port || bank > 2) return;
    if (write ? p_.write_port(bank, ins_.type) : p_.read_port(bank, ins_.type)) return;
    const std::string there = p_.port_numbers(bank, write);
    const std::string reaches = there == "none" ? "no port" : (there.find(',') == std::string::npos ? "port " : "ports ") + there;
    d_.warning(operand_loc(s_, Field::Type), "port " + std::to_string(ins_.type) + " of bank " + std::to_string(bank) +
                                                 " does not exist on " + std::string(p_.title) + " (" + (write ? "SIO" : "GIO") +
                                                 " reaches " + reaches + " of bank " + std::to_string(bank) + ")",
               "target");
  }

  void velocity(Op op) {
    if ((op == Op::ROR || op == Op::ROL))
      if (const ParamInfo* speed = p_.axis_param(kApTargetSpeed); speed && !accepts(*speed, ins_.value))
        generic_note(d_.warning(operand_loc(s_, Field::Value), "velocity " + std::to_string(ins_.value) +
                                                                   " is outside the range of " + std::string(p_.title) +
                                                                   " (" + range_text(*speed) + ")", "target"));
  }

  // The checks of a generic profile: values of the parameters its tables list.
  void generic_ranges(Op op) {
    velocity(op);
    if (!writes_immediate(op)) return;
    const bool axis = has_role(*s_.op, Role::AxisParam);
    if (!axis && ins_.motor != 0 && ins_.motor != 3) return;  // user variables and other banks: any value
    const ParamInfo* p = axis ? p_.axis_param(ins_.type) : p_.global_param(ins_.motor, ins_.type);
    if (p) check_param(op, *p, axis ? "axis parameter" : "global parameter", operand_loc(s_, Field::Type));
  }

  // Under the generic profile a range is that of its tables (docs/profiles.md): say so.
  void generic_note(Diagnostic& d) {
    if (p_.any_parameter)
      d_.note(d, SourceLoc{s_.loc.file, s_.loc.line, 0, 0}, "the generic profile checks values against its parameter tables, as tmclrun does; "
                         "-t MODULE checks them against your module's");
  }

  void axis(Op op) {
    const ParamInfo* p = p_.axis_param(ins_.type);
    SourceLoc at = operand_loc(s_, Field::Type);
    if (!p) {
      renumbering_hint(d_.warning(at, "axis parameter " + std::to_string(ins_.type) + " does not exist on " + std::string(p_.title), "target"),
                       ParamTable::Axis, "axis parameter", at);
      return;
    }
    check_param(op, *p, "axis parameter", at);
  }

  void global(Op op) {
    int bank = ins_.motor;
    SourceLoc at = operand_loc(s_, Field::Type);
    if (bank == 2) {
      if (ins_.type >= p_.user_vars)
        d_.warning(at, "user variable " + std::to_string(ins_.type) + " does not exist on " + std::string(p_.title) +
                           " (0 to " + std::to_string(p_.user_vars - 1) + ")", "target");
      else if ((op == Op::STGP || op == Op::RSGP) && ins_.type >= p_.eeprom_user_vars)
        d_.warning(at, "user variable " + std::to_string(ins_.type) + " cannot be stored in the EEPROM of " +
                           std::string(p_.title) + " (only 0 to " + std::to_string(p_.eeprom_user_vars - 1) + ")", "target");
      return;
    }
    if (bank != 0 && !(bank == 3 && !p_.bank3.empty())) {
      d_.warning(operand_loc(s_, Field::Motor), "bank " + std::to_string(bank) + " does not exist on " +
                                                    std::string(p_.title) +
                                                    (p_.bank3.empty() ? " (banks 0 and 2)" : " (banks 0, 2 and 3)"), "target");
      return;
    }
    const ParamInfo* p = p_.global_param(bank, ins_.type);
    if (!p) {
      renumbering_hint(d_.warning(at, "global parameter " + std::to_string(ins_.type) + " of bank " + std::to_string(bank) +
                                          " does not exist on " + std::string(p_.title), "target"),
                       bank == 0 ? ParamTable::Bank0 : ParamTable::Bank3,
                       bank == 0 ? "global parameter" : "bank 3 parameter", at);
      return;
    }
    check_param(op, *p, "global parameter", at);
  }

  // A number this module lacks that another bundled module gives a parameter this one has at
  // another number (param_names.hpp): say which, with a fix-it to this module's number.
  void renumbering_hint(Diagnostic& d, ParamTable table, const char* kind, SourceLoc at) {
    for (const Renumbered& r : renumbered(p_, table, ins_.type)) {
      std::string modules;
      for (std::size_t i = 0; i < r.elsewhere.size(); ++i)
        modules += std::string(i == 0 ? "" : i + 1 == r.elsewhere.size() ? " and " : ", ") + std::string(r.elsewhere[i]->name);
      const std::string number = std::to_string(r.here->number);
      d_.note(d, at, std::string(kind) + " " + std::to_string(ins_.type) + " is '" + std::string(r.name) + "' on " + modules +
                         (r.same_name ? "; here that is " : "; the nearest name here is ") + kind + " " + number + " ('" +
                         std::string(r.here->name) + "')");
      SourceLoc end = at;
      end.col += at.len;
      d.fixes.push_back({"use " + std::string(kind) + " " + number + " (" + std::string(r.here->name) + ")", at, end, number});
    }
  }

  // `kind` is "axis parameter" or "global parameter"; the parameter's text ("axis parameter 4
  // (Maximum positioning speed)") is built only for a warning: most instructions have none.
  void check_param(Op op, const ParamInfo& p, const char* kind, SourceLoc at) {
    const bool generic = p_.any_parameter;  // no access checks
    auto what = [&] { return param_text(kind, ins_.type, &p); };
    if (!generic && writes(op) && !(p.access & kWrite)) d_.warning(at, what() + " is read-only", "target");
    if (!generic && (op == Op::GAP || op == Op::GGP || op == Op::GAPX) && !(p.access & kRead))
      d_.warning(at, what() + " cannot be read", "target");
    // STAP/RSAP need E; STGP/RSGP take E or A (an auto-stored parameter has its EEPROM copy too),
    // as the VM and the module answer: else "wrong type" (status 3).
    const bool axis_store = op == Op::STAP || op == Op::RSAP, global_store = op == Op::STGP || op == Op::RSGP;
    if (!generic && ((axis_store && !(p.access & kEeprom)) || (global_store && !(p.access & (kEeprom | kAutoStore)))))
      d_.warning(at, what() + " is not stored in the EEPROM of " + std::string(p_.title), "target");
    if (writes_immediate(op) && ((p.access & kWrite) || generic) && !accepts(p, ins_.value))
      generic_note(d_.warning(operand_loc(s_, Field::Value),
                              "value " + std::to_string(ins_.value) + " is outside the range of " + what() + ": " + range_text(p),
                              "target"));
    // A negative number for a parameter with no negative values: in range only as the unsigned
    // number its 32 bits also are. "Unsigned" is what the profile's range says (its minimum).
    else if (writes_immediate(op) && ((p.access & kWrite) || generic) && negative_ && p.min >= 0)
      d_.warning(operand_loc(s_, Field::Value),
                 "value " + std::to_string(ins_.value) + " is negative, but " + what() + " takes no negative values (" +
                     range_text(p) + "): the module reads it as " +
                     std::to_string(static_cast<std::uint32_t>(ins_.value)),
                 "target");
  }

  const Profile& p_;
  const Stmt& s_;
  const Instruction& ins_;
  Diagnostics& d_;
  bool negative_;
};

}  // namespace

void check_against_profile(const Profile& profile, const Stmt& stmt, const Instruction& ins, Diagnostics& diags,
                           bool negative_value) {
  Checker(profile, stmt, ins, diags, negative_value).run();
}

}  // namespace tmcl::detail
