// Instruction semantics, one function per row of opcodes.def, shared by standalone mode (the run
// loop in vm_exec.cpp, kDirect = false) and direct mode (vm_direct.cpp, kDirect = true).
// Internal to the vm library. In standalone mode every op leaves pc at the next instruction to
// run; in direct mode pc, the accumulator and the flags of reads are left alone.
// Decisions where the manuals are silent are numbered in docs/errata.md (E1, E2, ...).
#pragma once

#include <cstdint>
#include <limits>
#include <utility>

#include "tmcl/vm.hpp"

namespace tmcl::ops {

// The instruction semantics' door to the VM's private run-loop state (vm.hpp befriends it).
struct Internal {
  // Something changed that the run loop must look at before the next instruction.
  static void recheck(Vm& vm) { vm.next_check_ = 0; }
  static bool jump_ok(Vm& vm, std::int32_t target) { return vm.jump_ok(target); }
  static bool vector_ok(const Vm& vm, int n) { return vm.vector_ok(n); }
  static void fault(Vm& vm, std::string message) { vm.fault(std::move(message)); }
  // A run-time warning; true when --strict made it a fault (then pc stays on the instruction).
  static bool warn(Vm& vm, RuntimeWarning::Kind k, std::string message) { return vm.warn(k, std::move(message)); }
  static bool note_not_simulated(Vm& vm, int vector) { return vm.note_not_simulated(vector); }
  static bool note_not_simulated_param(Vm& vm, int bank, const Instruction& i, bool read) {
    return vm.note_not_simulated_param(bank, i.type, op_info(i.op)->mnemonic, read);
  }
};

using R = DirectReply;
inline constexpr R ok(std::int32_t v = 0) { return {kStatusOk, v}; }
inline constexpr R status(std::uint8_t s, std::int32_t v = 0) { return {s, v}; }

// E2: results and reads set ZE/EQ from "value == 0" and GT/LT from its sign.
// (Written without branches: these run on the dispatch fast path.)
inline std::uint8_t compare_flags(std::int32_t a, std::int32_t b) {
  return static_cast<std::uint8_t>((a == b) * (kFlagZero | kFlagEqual) + (a > b) * kFlagGreater + (a < b) * kFlagLower);
}
inline std::uint8_t flags_of(std::int32_t v) { return compare_flags(v, 0); }

template <bool kDirect>
inline void next(Vm& vm) {
  if constexpr (!kDirect) ++vm.pc;
}

// A read: standalone loads the accumulator and sets the flags; direct replies with the value.
template <bool kDirect>
inline R load(Vm& vm, std::uint8_t st, std::int32_t v) {
  if constexpr (!kDirect) {
    if (st == kStatusOk) {
      vm.acc = v;
      vm.flags = flags_of(v);
    }
  }
  next<kDirect>(vm);
  return {st, st == kStatusOk ? v : 0};
}

template <bool kDirect>
inline R done(Vm& vm, std::uint8_t st, std::int32_t v = 0) {
  next<kDirect>(vm);
  return {st, v};
}

// E1: two's-complement wrap-around for ADD/SUB/MUL; DIV and MOD by zero leave the target
// unchanged; INT_MIN / -1 wraps to INT_MIN, INT_MIN % -1 is 0; DIV truncates toward zero and MOD
// takes the sign of the dividend (C semantics, as the firmware is written in C).
// The CALC types by name (ADD ... COMP), from keywords.def: CALCVV's set has every one of them.
using namespace kw::CalcVV;

inline std::int32_t wrap(std::uint32_t v) { return static_cast<std::int32_t>(v); }

// a <op> b for ADD..XOR and LOAD, the operation known at compile time: the run loop's fast path
// (vm_exec.cpp) instantiates it per CALC type, so each case is one machine instruction or two that
// no inlining decision of the compiler can move out of the loop (issue 42: an out-of-line
// arith() with the accumulator spilled to memory made the CALC/DJNZ loop 1.6x slower).
// NOT/SWAP/COMP are handled by the callers.
template <int kOp>
inline std::int32_t arith_of(std::int32_t a, std::int32_t b) {
  const auto ua = static_cast<std::uint32_t>(a), ub = static_cast<std::uint32_t>(b);
  if constexpr (kOp == ADD) return wrap(ua + ub);
  else if constexpr (kOp == SUB) return wrap(ua - ub);
  else if constexpr (kOp == MUL) return wrap(ua * ub);
  else if constexpr (kOp == DIV) return b == 0 ? a : (a == std::numeric_limits<std::int32_t>::min() && b == -1) ? a : a / b;
  else if constexpr (kOp == MOD) return b == 0 ? a : (b == -1) ? 0 : a % b;
  else if constexpr (kOp == AND) return wrap(ua & ub);
  else if constexpr (kOp == OR) return wrap(ua | ub);
  else if constexpr (kOp == XOR) return wrap(ua ^ ub);
  else if constexpr (kOp == LOAD) return b;
  else return a;
}
// The same with the operation known at run time (the table dispatch).
inline void arith(std::uint8_t op, std::int32_t& a, std::int32_t b) {
  switch (op) {
#define TMCL_ARITH_CASE(t) \
  case t: a = arith_of<t>(a, b); break;
    TMCL_ARITH_CASE(ADD)
    TMCL_ARITH_CASE(SUB)
    TMCL_ARITH_CASE(MUL)
    TMCL_ARITH_CASE(DIV)
    TMCL_ARITH_CASE(MOD)
    TMCL_ARITH_CASE(AND)
    TMCL_ARITH_CASE(OR)
    TMCL_ARITH_CASE(XOR)
    TMCL_ARITH_CASE(LOAD)
#undef TMCL_ARITH_CASE
    default: break;
  }
}

// The CALC family: `a` is the target, `b` the operand. `max_op` is the highest type the
// instruction accepts; `not_self` chooses NOT = ~a (CALC, CALCV) or NOT = ~b (the others, which
// "copy the inverted operand"); `b_writable` allows SWAP.
template <bool kDirect>
inline R calc(Vm& vm, const Instruction& ins, std::int32_t& a, std::int32_t* b_ref, std::int32_t b, bool not_self,
              bool allow_swap, bool allow_comp) {
  std::uint8_t op = ins.type;
  if (op > COMP || (op == SWAP && !allow_swap) || (op == COMP && !allow_comp)) return done<kDirect>(vm, kStatusWrongType);
  switch (op) {
    case NOT: a = not_self ? ~a : ~b; vm.flags = flags_of(a); break;
    case SWAP: std::swap(a, *b_ref); vm.flags = flags_of(a); break;
    case COMP: vm.flags = compare_flags(a, b); break;
    default: arith(op, a, b); vm.flags = flags_of(a); break;
  }
  return done<kDirect>(vm, kStatusOk, ins.value);
}

// JC/CALL conditions as data: the flag bits that must be set (`mask`, over the comparison flags
// in the low nibble and the error flags in the high one) or, with `invert`, all be clear.
struct CondBits {
  std::uint8_t mask;
  bool invert;
};
inline constexpr CondBits kConditions[16] = {
    {kFlagZero, false},  {kFlagZero, true},  {kFlagEqual, false}, {kFlagEqual, true},
    {kFlagGreater, false}, {kFlagGreater | kFlagEqual, false}, {kFlagLower, false}, {kFlagLower | kFlagEqual, false},
    {kErrTimeout << 4, false}, {kErrAlarm << 4, false}, {kErrDeviation << 4, false}, {kErrPosition << 4, false},
    {0, false}, {0, false}, {0, false}, {0, false},  // E11: unknown conditions never hold
};
static_assert(kw::Cond::ZE == 0 && kw::Cond::NZ == 1 && kw::Cond::EQ == 2 && kw::Cond::NE == 3 && kw::Cond::GT == 4 &&
              kw::Cond::GE == 5 && kw::Cond::LT == 6 && kw::Cond::LE == 7 && kw::Cond::ETO == 8 && kw::Cond::EAL == 9 &&
              kw::Cond::EDV == 10 && kw::Cond::EPO == 11,
              "kConditions is indexed by the JC conditions of keywords.def");
inline bool condition(std::uint8_t flags, std::uint8_t errors, std::uint8_t cond) {
  if (cond > 15) return false;
  const CondBits c = kConditions[cond];
  const unsigned bits = flags | (static_cast<unsigned>(errors) << 4);
  return ((bits & c.mask) != 0) != c.invert;
}
inline bool condition(const Vm& vm, std::uint8_t cond) { return condition(vm.flags, vm.errors, cond); }

// Flow-control commands have no effect in direct mode (E14) and reply ok with the value.
#define TMCL_FLOW_IN_DIRECT(ins) \
  if constexpr (D) return ok((ins).value)

// Opcodes the run loop's code[] uses for pre-decoded hot forms. No program opcode is 0x80 or
// higher (the control commands up there never reach code[]), so these cannot collide:
//   kFastCalc + t     CALC t         (t = ADD..LOAD)
//   kFastCalcV + t    CALCV t        (t = ADD..LOAD, COMP)
//   kFusedCalc + t    CALC t, then the DJNZ at the next address (a superinstruction)
//   kFusedCalcV + t   CALCV t, then the DJNZ at the next address
//   kFastJA, kFastDJNZ   JA, DJNZ whose target lies inside the program (one outside it keeps its
//                        own opcode and faults through the table dispatch)
//   kFastJC           JC whose target lies inside the program, its condition pre-decoded: type
//                     the mask of kConditions, motor its invert
// A fused form still counts two instructions and two instruction times, and the run loop splits
// it when a check falls between the two, so fusion never changes what a program observes.
inline constexpr std::uint8_t kFastCalc = 0xC0;
inline constexpr std::uint8_t kFastCalcV = 0xD0;
inline constexpr std::uint8_t kFusedCalc = 0xA0;
inline constexpr std::uint8_t kFusedCalcV = 0xB0;
inline constexpr std::uint8_t kFastJA = 0x90;
inline constexpr std::uint8_t kFastJC = 0x91;
inline constexpr std::uint8_t kFastDJNZ = 0x92;
// The pre-decoded JC's condition (kFastJC): as condition(), from the mask and invert in the form.
inline bool fast_condition(std::uint8_t flags, std::uint8_t errors, const Instruction& jc) {
  const unsigned bits = flags | (static_cast<unsigned>(errors) << 4);
  return ((bits & jc.type) != 0) != (jc.motor != 0);
}

// What the run loop executes at an address holding `ins`, followed by `next`, in a program of
// `size` instructions: 0 when the profile lacks the command (or it is not a program
// instruction), a pre-decoded hot form, or the instruction itself.
inline Instruction decode_for_run(const Instruction& ins, const Instruction& next, std::int32_t size,
                                  const Profile& profile) {
  auto available = [&](const Instruction& i) {
    const OpInfo* info = op_info(i.op);
    return info && !info->control && profile.has_command(i.op);
  };
  Instruction c = ins;
  if (!available(ins)) {
    c.op = 0;
    return c;
  }
  const bool djnz_next = next.op == static_cast<std::uint8_t>(Op::DJNZ) && available(next) && next.value >= 0 &&
                         next.value < size;
  const bool target_ok = ins.value >= 0 && ins.value < size;
  if (ins.op == static_cast<std::uint8_t>(Op::JA) && target_ok) {
    c.op = kFastJA;
  } else if (ins.op == static_cast<std::uint8_t>(Op::DJNZ) && target_ok) {
    c.op = kFastDJNZ;
  } else if (ins.op == static_cast<std::uint8_t>(Op::JC) && target_ok) {
    const CondBits cond = ins.type <= 15 ? kConditions[ins.type] : CondBits{0, false};
    c.op = kFastJC;
    c.type = cond.mask;
    c.motor = cond.invert ? 1 : 0;
  } else if (ins.op == static_cast<std::uint8_t>(Op::CALC) && ins.type <= LOAD) {
    c.op = static_cast<std::uint8_t>((djnz_next ? kFusedCalc : kFastCalc) + ins.type);
  } else if (ins.op == static_cast<std::uint8_t>(Op::CALCV) && (ins.type <= LOAD || ins.type == COMP)) {
    c.op = static_cast<std::uint8_t>((djnz_next && ins.type != COMP ? kFusedCalcV : kFastCalcV) + ins.type);
  }
  return c;
}

inline bool var_index(std::int32_t v) { return v >= 0 && v <= 255; }

// E3: a write the module refuses for its value (status 4, the value outside the range the
// profile gives the parameter) is ignored in standalone mode, as on the module, with a run-time
// warning naming parameter, value and range; with --strict it is a fault (pc stays). Direct mode
// replies status 4, as the module does.
template <bool D>
R refused_value(Vm& vm, std::uint8_t st, bool axis, int bank, int param, const char* what, std::int64_t value) {
  if constexpr (!D) {
    const ParamInfo* p = st == kStatusInvalidValue ? vm.range_refusing(axis, bank, param, value) : nullptr;
    if (p && Internal::warn(vm, RuntimeWarning::ValueOutOfRange,
                            std::string(what) + " " + std::to_string(value) + " is outside the range of " +
                                param_text(axis ? "axis parameter" : "global parameter", param, p) +
                                (axis ? "" : " of bank " + std::to_string(bank)) + ": " + range_text(*p)))
      return ok();
  }
  return done<D>(vm, st);
}
// E51: an instruction naming a motor the module lacks is ignored (status 4 in direct mode), with
// a run-time warning naming instruction, motor and the motors there are; true when it was
// missing (then the caller returns `r`, which is ok() when --strict made it a fault).
template <bool D> bool motor_missing(Vm& vm, const Instruction& i, R& r) {
  if (vm.motor_ok(i.motor)) return false;
  if constexpr (!D) {
    const int motors = vm.profile->motors;
    if (Internal::warn(vm, RuntimeWarning::NoSuchMotor,
                       std::string(op_info(i.op)->mnemonic) + " on motor " + std::to_string(i.motor) + ": " +
                           std::string(vm.profile->title) + " has no motor " + std::to_string(i.motor) +
                           (motors == 1 ? std::string(" (motor 0 only)") : " (motors 0 to " + std::to_string(motors - 1) + ")"))) {
      r = ok();
      return true;
    }
  }
  r = done<D>(vm, kStatusInvalidValue);
  return true;
}
// E51: a write of a parameter that is read-only or that the module does not have (status 3).
template <bool D> R refused_param(Vm& vm, const Instruction& i, bool axis, int bank, std::int64_t value) {
  if constexpr (!D) {
    const ParamInfo* p = axis ? vm.profile->axis_param(i.type) : vm.profile->global_param(bank, i.type);
    const std::string what = param_text(axis ? "axis parameter" : "global parameter", i.type, p) +
                             (axis ? "" : " of bank " + std::to_string(bank));
    if ((axis || bank == 0 || bank == 3) &&
        Internal::warn(vm, RuntimeWarning::NotWritable,
                       std::string(op_info(i.op)->mnemonic) + " of value " + std::to_string(value) + ": " + what +
                           (p ? std::string(" is read-only") : " does not exist on " + std::string(vm.profile->title))))
      return ok();
  }
  return done<D>(vm, kStatusWrongType);
}
// E77: an instruction that used a parameter (axis: bank -1) the profile marks not-simulated: a
// note once per run (--strict: a fault, pc left on it).
template <bool D> R used(Vm& vm, const Instruction& i, int bank, std::uint8_t st, bool read, std::int32_t v = 0) {
  if constexpr (!D)
    if (st == kStatusOk && Internal::note_not_simulated_param(vm, bank, i, read)) return ok();
  return read ? load<D>(vm, st, v) : done<D>(vm, st);
}
template <bool D> R set_axis(Vm& vm, const Instruction& i, std::int32_t value) {
  if (R r{}; motor_missing<D>(vm, i, r)) return r;
  const std::uint8_t st = vm.set_axis(i.motor, i.type, value);
  if (D || st == kStatusOk) return used<D>(vm, i, -1, st, false);
  if (st == kStatusWrongType) return refused_param<D>(vm, i, true, 0, value);
  return refused_value<D>(vm, st, true, 0, i.type, "value", value);
}
template <bool D> R set_global(Vm& vm, const Instruction& i, std::int32_t value) {
  const std::uint8_t st = vm.set_global(i.motor, i.type, value);
  if (D || st == kStatusOk) return used<D>(vm, i, i.motor, st, false);
  if (st == kStatusWrongType) return refused_param<D>(vm, i, false, i.motor, value);
  return refused_value<D>(vm, st, false, i.motor, i.type, "value", value);
}
template <bool D> R rotate(Vm& vm, const Instruction& i, std::int64_t velocity) {
  if (R r{}; motor_missing<D>(vm, i, r)) return r;
  const std::uint8_t st = vm.rotate(i.motor, velocity);
  if (D || st == kStatusOk) return done<D>(vm, st);
  return refused_value<D>(vm, st, true, 0, kApTargetSpeed, "velocity", velocity);
}
// E53: GIO/SIO of a port the module does not have: ignored (status 3), with a warning naming the
// ports of that bank there are.
template <bool D> R refused_port(Vm& vm, const Instruction& i, std::uint8_t st, bool write) {
  if constexpr (!D) {
    if (st == kStatusWrongType &&
        Internal::warn(vm, RuntimeWarning::NoSuchPort,
                       std::string(write ? "SIO " : "GIO ") + std::to_string(i.type) + ", " + std::to_string(i.motor) + ": " +
                           std::string(vm.profile->title) + " has no port " + std::to_string(i.type) + " in bank " +
                           std::to_string(i.motor) + " (" + (write ? "SIO" : "GIO") + ": " + vm.ports_text(i.motor, write) + ")"))
      return ok();
  }
  return done<D>(vm, st);
}

// ---------------------------------------------------------------- motion
template <bool D> R op_ROR(Vm& vm, const Instruction& i) { return rotate<D>(vm, i, i.value); }
template <bool D> R op_ROL(Vm& vm, const Instruction& i) { return rotate<D>(vm, i, -static_cast<std::int64_t>(i.value)); }
template <bool D> R op_MST(Vm& vm, const Instruction& i) {
  if (R r{}; motor_missing<D>(vm, i, r)) return r;
  return done<D>(vm, vm.motor_stop(i.motor));
}
// E47: a positioning the ramp cannot start (or whose ramp the manual forbids) is run as the core
// plans it, with a run-time warning naming the parameter (a fault under --strict).
template <bool D> R move(Vm& vm, const Instruction& i, std::int32_t value) {
  if (R r{}; motor_missing<D>(vm, i, r)) return r;
  const std::uint8_t st = vm.move(i.type, i.motor, value);
  if constexpr (!D) {
    // M32: MVP COORD the module refuses (status 3 without coordinates, 4 for one it lacks): ignored.
    if (i.type == kw::Move::COORD && st != kStatusOk) {
      const int coords = vm.profile->coords;
      if (Internal::warn(vm, RuntimeWarning::NoSuchCoordinate,
                         "MVP COORD of coordinate " + std::to_string(value) + ": " + std::string(vm.profile->title) +
                             (coords == 0 ? std::string(" has no coordinates (its MVP takes ABS and REL)")
                                          : " has coordinates 0 to " + std::to_string(coords - 1))))
        return ok();
    }
    // An MVP type the module does not have (from a .bin; tmclasm warns of it, -Wkeyword-value):
    // status 3 and ignored, as by the module, with a warning naming the types there are (E80).
    if (st == kStatusWrongType && i.type != kw::Move::COORD &&
        Internal::warn(vm, RuntimeWarning::NoSuchType,
                       std::to_string(i.type) + " is not a valid move type of " + std::string(op_info(i.op)->mnemonic) + ": " +
                           std::string(vm.profile->title) +
                           (vm.profile->coords == 0 ? " moves by ABS (0) and REL (1)" : " moves by ABS (0), REL (1) and COORD (2)")))
      return ok();
    if (st == kStatusOk)
      if (std::string why = vm.motion->move_problem(i.motor); !why.empty())
        if (Internal::warn(vm, RuntimeWarning::RampSetting, "MVP on motor " + std::to_string(i.motor) + ": " + why)) return ok();
  }
  return done<D>(vm, st);
}
template <bool D> R op_MVP(Vm& vm, const Instruction& i) { return move<D>(vm, i, i.value); }
template <bool D> R op_MVPA(Vm& vm, const Instruction& i) { return move<D>(vm, i, vm.acc); }
template <bool D> R op_MVPXA(Vm& vm, const Instruction& i) { return op_MVPA<D>(vm, i); }
template <bool D> R op_RORA(Vm& vm, const Instruction& i) { return rotate<D>(vm, i, vm.acc); }
template <bool D> R op_ROLA(Vm& vm, const Instruction& i) { return rotate<D>(vm, i, -static_cast<std::int64_t>(vm.acc)); }
template <bool D> R op_RORXA(Vm& vm, const Instruction& i) { return op_RORA<D>(vm, i); }
template <bool D> R op_ROLXA(Vm& vm, const Instruction& i) { return op_ROLA<D>(vm, i); }
template <bool D> R op_MSTX(Vm& vm, const Instruction& i) { return op_MST<D>(vm, i); }
template <bool D> R op_RFS(Vm& vm, const Instruction& i) {
  if (R r{}; motor_missing<D>(vm, i, r)) return r;
  std::int32_t v = 0;
  std::uint8_t st = vm.rfs(i.type, i.motor, v);
  if (i.type == kw::Rfs::STATUS) return load<D>(vm, st, v);  // a read
  return done<D>(vm, st);
}

// ---------------------------------------------------------------- parameters
template <bool D> R op_SAP(Vm& vm, const Instruction& i) { return set_axis<D>(vm, i, i.value); }
template <bool D> R op_GAP(Vm& vm, const Instruction& i) {
  if (R r{}; motor_missing<D>(vm, i, r)) return r;
  std::int32_t v = 0;
  std::uint8_t st = vm.get_axis(i.motor, i.type, v);
  return used<D>(vm, i, -1, st, true, v);
}
template <bool D> R op_AAP(Vm& vm, const Instruction& i) { return set_axis<D>(vm, i, vm.acc); }
template <bool D> R op_SAPX(Vm& vm, const Instruction& i) { return op_SAP<D>(vm, i); }
template <bool D> R op_GAPX(Vm& vm, const Instruction& i) { return op_GAP<D>(vm, i); }
template <bool D> R op_AAPX(Vm& vm, const Instruction& i) { return op_AAP<D>(vm, i); }
template <bool D> R op_STAP(Vm& vm, const Instruction& i) {
  if (R r{}; motor_missing<D>(vm, i, r)) return r;
  return used<D>(vm, i, -1, vm.store_axis(i.motor, i.type), false);
}
template <bool D> R op_RSAP(Vm& vm, const Instruction& i) {
  if (R r{}; motor_missing<D>(vm, i, r)) return r;
  return used<D>(vm, i, -1, vm.restore_axis(i.motor, i.type), false);
}
template <bool D> R op_SGP(Vm& vm, const Instruction& i) { return set_global<D>(vm, i, i.value); }
template <bool D> R op_GGP(Vm& vm, const Instruction& i) {
  std::int32_t v = 0;
  std::uint8_t st = vm.get_global(i.motor, i.type, v);
  return used<D>(vm, i, i.motor, st, true, v);
}
template <bool D> R op_AGP(Vm& vm, const Instruction& i) { return set_global<D>(vm, i, vm.acc); }
template <bool D> R op_STGP(Vm& vm, const Instruction& i) { return used<D>(vm, i, i.motor, vm.store_global(i.motor, i.type), false); }
template <bool D> R op_RSGP(Vm& vm, const Instruction& i) { return used<D>(vm, i, i.motor, vm.restore_global(i.motor, i.type), false); }
template <bool D> R op_SIO(Vm& vm, const Instruction& i) {
  // SIO 255, 2, -1: the accumulator's lower 8 bits to the outputs (TMCL reference 3.14).
  const std::int32_t v = i.type == 255 && i.value == -1 ? (vm.acc & 0xFF) : i.value;
  const std::uint8_t st = vm.set_io(i.type, i.motor, v);
  if (st == kStatusOk) return done<D>(vm, st);
  return refused_port<D>(vm, i, st, true);
}
template <bool D> R op_GIO(Vm& vm, const Instruction& i) {
  std::int32_t v = 0;
  std::uint8_t st = vm.get_io(i.type, i.motor, v);
  if (st != kStatusOk) return refused_port<D>(vm, i, st, false);
  return load<D>(vm, st, v);
}

// ---------------------------------------------------------------- coordinates
// M32: SCO, ACO, GCO, CCO of a coordinate the module lacks (status 3): ignored, with the
// no-such-coordinate warning of MVP COORD (--strict: a fault); true when the caller is done.
template <bool D> bool coord_missing(Vm& vm, const Instruction& i, std::uint8_t st, R& r) {
  if constexpr (!D) {
    if (st == kStatusWrongType &&
        Internal::warn(vm, RuntimeWarning::NoSuchCoordinate,
                       std::string(op_info(i.op)->mnemonic) + " of coordinate " + std::to_string(i.type) + ": " +
                           std::string(vm.profile->title) + " has coordinates 0 to " + std::to_string(vm.profile->coords - 1))) {
      r = ok();
      return true;
    }
  }
  return false;
}
template <bool D> R op_SCO(Vm& vm, const Instruction& i) {
  const std::uint8_t st = vm.set_coord(i.motor, i.type, i.value);
  if (R r{}; coord_missing<D>(vm, i, st, r)) return r;
  return done<D>(vm, st);
}
template <bool D> R op_ACO(Vm& vm, const Instruction& i) {
  if (i.motor == 255) return done<D>(vm, kStatusInvalidValue);  // the EEPROM forms are SCO/GCO only
  const std::uint8_t st = vm.set_coord(i.motor, i.type, vm.acc);
  if (R r{}; coord_missing<D>(vm, i, st, r)) return r;
  return done<D>(vm, st);
}
template <bool D> R op_GCO(Vm& vm, const Instruction& i) {
  std::int32_t v = 0;
  std::uint8_t st = vm.get_coord(i.motor, i.type, v);
  if (R r{}; coord_missing<D>(vm, i, st, r)) return r;
  if (i.motor == 255) return done<D>(vm, st);  // EEPROM -> RAM copy: not a read
  return load<D>(vm, st, v);
}
template <bool D> R op_CCO(Vm& vm, const Instruction& i) {
  std::int32_t v = 0;
  std::uint8_t st = vm.capture_coord(i.motor, i.type, v);
  if (R r{}; coord_missing<D>(vm, i, st, r)) return r;
  return done<D>(vm, st, st == kStatusOk ? v : 0);  // E9: a capture, not a read: acc untouched
}

// ---------------------------------------------------------------- arithmetic
template <bool D> R op_CALC(Vm& vm, const Instruction& i) {
  return calc<D>(vm, i, vm.acc, nullptr, i.value, true, false, false);
}
template <bool D> R op_CALCX(Vm& vm, const Instruction& i) {
  if (i.type == LOAD) {  // "copy accumulator to X register"
    vm.x = vm.acc;
    vm.flags = flags_of(vm.x);
    return done<D>(vm, kStatusOk);
  }
  return calc<D>(vm, i, vm.acc, &vm.x, vm.x, false, true, false);
}
template <bool D> R op_COMP(Vm& vm, const Instruction& i) {
  vm.flags = compare_flags(vm.acc, i.value);
  return done<D>(vm, kStatusOk, i.value);
}
// The manual's replies: CALCVV/VA/AV/VX/XV answer 0, CALC and CALCV echo the operand.
template <bool D> R op_CALCVV(Vm& vm, const Instruction& i) {
  if (!var_index(i.value)) return done<D>(vm, kStatusInvalidValue);
  std::int32_t& b = vm.vars[static_cast<std::uint8_t>(i.value)];
  return {calc<D>(vm, i, vm.vars[i.motor], &b, b, false, true, true).status, 0};
}
template <bool D> R op_CALCVA(Vm& vm, const Instruction& i) {
  return {calc<D>(vm, i, vm.vars[i.motor], &vm.acc, vm.acc, false, true, true).status, 0};
}
template <bool D> R op_CALCAV(Vm& vm, const Instruction& i) {
  std::int32_t& b = vm.vars[i.motor];
  return {calc<D>(vm, i, vm.acc, &b, b, false, true, true).status, 0};
}
template <bool D> R op_CALCVX(Vm& vm, const Instruction& i) {
  return {calc<D>(vm, i, vm.vars[i.motor], &vm.x, vm.x, false, true, true).status, 0};
}
template <bool D> R op_CALCXV(Vm& vm, const Instruction& i) {
  std::int32_t& b = vm.vars[i.motor];
  return {calc<D>(vm, i, vm.x, &b, b, false, true, true).status, 0};
}
template <bool D> R op_CALCV(Vm& vm, const Instruction& i) {
  return calc<D>(vm, i, vm.vars[i.motor], nullptr, i.value, true, false, true);
}

// ---------------------------------------------------------------- indexed variables, stack
// E8: SIV/GIV/AIV with X outside 0..255 are ignored (the manuals say so).
template <bool D> R op_SIV(Vm& vm, const Instruction& i) {
  if (!var_index(vm.x)) return done<D>(vm, kStatusInvalidValue);
  vm.vars[static_cast<std::size_t>(vm.x)] = i.value;
  return done<D>(vm, kStatusOk);
}
template <bool D> R op_GIV(Vm& vm, const Instruction& i) {
  (void)i;
  if (!var_index(vm.x)) return done<D>(vm, kStatusInvalidValue);
  return load<D>(vm, kStatusOk, vm.vars[static_cast<std::size_t>(vm.x)]);
}
template <bool D> R op_AIV(Vm& vm, const Instruction& i) {
  (void)i;
  if (!var_index(vm.x)) return done<D>(vm, kStatusInvalidValue);
  vm.vars[static_cast<std::size_t>(vm.x)] = vm.acc;
  return done<D>(vm, kStatusOk);
}
// E12: PUSH*/POP* use their own 8-entry stack; a push on a full or a pop on an empty one is ignored.
template <bool D> R push(Vm& vm, std::int32_t v) {
  if (vm.dsp < Vm::kStackDepth) vm.data_stack[static_cast<std::size_t>(vm.dsp++)] = v;
  return done<D>(vm, kStatusOk);
}
template <bool D> R pop(Vm& vm, std::int32_t& dst) {
  if (vm.dsp > 0) dst = vm.data_stack[static_cast<std::size_t>(--vm.dsp)];
  return done<D>(vm, kStatusOk);
}
template <bool D> R op_PUSHA(Vm& vm, const Instruction&) { return push<D>(vm, vm.acc); }
template <bool D> R op_PUSHX(Vm& vm, const Instruction&) { return push<D>(vm, vm.x); }
template <bool D> R op_PUSHV(Vm& vm, const Instruction& i) { return push<D>(vm, vm.vars[i.type]); }
template <bool D> R op_POPA(Vm& vm, const Instruction&) { return pop<D>(vm, vm.acc); }
template <bool D> R op_POPX(Vm& vm, const Instruction&) { return pop<D>(vm, vm.x); }
template <bool D> R op_POPV(Vm& vm, const Instruction& i) { return pop<D>(vm, vm.vars[i.type]); }

// ---------------------------------------------------------------- control flow
template <bool D> R op_JA(Vm& vm, const Instruction& i) {
  TMCL_FLOW_IN_DIRECT(i);
  if (Internal::jump_ok(vm, i.value)) vm.pc = i.value;
  return ok();
}
template <bool D> R op_JC(Vm& vm, const Instruction& i) {
  TMCL_FLOW_IN_DIRECT(i);
  if (!condition(vm, i.type)) return done<D>(vm, kStatusOk);
  if (Internal::jump_ok(vm, i.value)) vm.pc = i.value;
  return ok();
}
template <bool D> R call(Vm& vm, const Instruction& i) {
  if (!Internal::jump_ok(vm, i.value)) return ok();
  if (vm.sp >= Vm::kStackDepth) {  // E5: the 9th CSUB is ignored
    if constexpr (!D)
      if (Internal::warn(vm, RuntimeWarning::CallStackFull,
                         std::string(op_info(i.op)->mnemonic) + " to " + std::to_string(i.value) +
                             " with the call stack full (8 return addresses)"))
        return ok();
    return done<D>(vm, kStatusOk);
  }
  vm.stack[static_cast<std::size_t>(vm.sp++)] = vm.pc + 1;
  vm.pc = i.value;
  return ok();
}
template <bool D> R op_CSUB(Vm& vm, const Instruction& i) {
  TMCL_FLOW_IN_DIRECT(i);
  return call<D>(vm, i);
}
template <bool D> R op_CALL(Vm& vm, const Instruction& i) {
  TMCL_FLOW_IN_DIRECT(i);
  if (!condition(vm, i.type)) return done<D>(vm, kStatusOk);
  return call<D>(vm, i);
}
template <bool D> R op_RSUB(Vm& vm, const Instruction& i) {
  TMCL_FLOW_IN_DIRECT(i);
  // E6: an empty stack, or (inside a handler) no frame pushed by the handler: ignored.
  int floor = vm.in_handler ? vm.saved.stack_depth : 0;
  if (vm.sp <= floor) {
    if constexpr (!D)
      if (Internal::warn(vm, RuntimeWarning::ReturnWithoutCall,
                         vm.in_handler ? "RSUB in the handler of interrupt " + std::to_string(vm.saved.vector) +
                                             ", which made no call to return from (a handler ends with RETI)"
                                       : std::string("RSUB with an empty call stack: nothing to return to")))
        return ok();
    return done<D>(vm, kStatusOk);
  }
  vm.pc = vm.stack[static_cast<std::size_t>(--vm.sp)];
  return ok();
}
template <bool D> R op_DJNZ(Vm& vm, const Instruction& i) {
  TMCL_FLOW_IN_DIRECT(i);
  std::int32_t& v = vm.vars[i.type];
  v = wrap(static_cast<std::uint32_t>(v) - 1u);  // E4: flags unchanged; jumps while != 0
  if (v == 0) return done<D>(vm, kStatusOk);
  if (Internal::jump_ok(vm, i.value)) vm.pc = i.value;
  return ok();
}
template <bool D> R op_STOP(Vm& vm, const Instruction& i) {
  TMCL_FLOW_IN_DIRECT(i);
  if (vm.in_handler &&
      Internal::warn(vm, RuntimeWarning::HandlerWithoutReti,
                     "STOP inside the handler of interrupt " + std::to_string(vm.saved.vector) + ": the handler is left without RETI"))
    return ok();
  vm.status = AppStatus::Stopped;
  vm.halt_pc = vm.pc;
  Internal::recheck(vm);
  return ok();
}
template <bool D> R op_RST(Vm& vm, const Instruction& i) {
  TMCL_FLOW_IN_DIRECT(i);
  if (!Internal::jump_ok(vm, i.value)) return ok();
  vm.reset_interpreter();
  vm.pc = i.value;
  return ok();
}
template <bool D> R op_WAIT(Vm& vm, const Instruction& i) {
  TMCL_FLOW_IN_DIRECT(i);
  std::int64_t ticks = i.value == -1 ? vm.acc : i.value;  // E7: -1 takes the accumulator
  if (ticks < 0) ticks = 0;                                // E7: negative counts as 0
  const bool timed = i.type == kw::Wait::TICKS;
  if (!timed && i.type <= kw::Wait::RFS)
    if (R r{}; motor_missing<D>(vm, i, r)) return r;  // ignored (E51: with a warning)
  if (i.type > kw::Wait::RFS) return done<D>(vm, kStatusOk);  // ignored
  SimTime start = vm.now - vm.instr_time;  // the WAIT's own start instant
  vm.wait.active = true;
  vm.wait.kind = i.type;
  vm.wait.motor = timed ? 0 : i.motor;
  vm.wait.deadline = (timed || ticks > 0) ? start + ticks * kUsPerTick : kNever;
  Internal::recheck(vm);
  return ok();  // pc stays on the WAIT until it ends (the run loop's slow path)
}

// ---------------------------------------------------------------- interrupts and errors
template <bool D> R op_EI(Vm& vm, const Instruction& i) {
  if (i.type == 255) {
    vm.global_enable = true;
  } else if (Internal::vector_ok(vm, i.type)) {
    if constexpr (!D)
      if (Internal::note_not_simulated(vm, i.type)) return ok();  // --strict: a fault
    vm.enabled[i.type >> 6] |= std::uint64_t{1} << (i.type & 63);
  } else {
    return done<D>(vm, kStatusWrongType);
  }
  Internal::recheck(vm);
  return done<D>(vm, kStatusOk);
}
template <bool D> R op_DI(Vm& vm, const Instruction& i) {
  if (i.type == 255) {
    vm.global_enable = false;
  } else if (Internal::vector_ok(vm, i.type)) {
    vm.enabled[i.type >> 6] &= ~(std::uint64_t{1} << (i.type & 63));
    vm.pending[i.type >> 6] &= ~(std::uint64_t{1} << (i.type & 63));  // E10: DI n drops a latched n
  } else {
    return done<D>(vm, kStatusWrongType);
  }
  return done<D>(vm, kStatusOk);
}
template <bool D> R op_VECT(Vm& vm, const Instruction& i) {
  if (!Internal::vector_ok(vm, i.type)) return done<D>(vm, kStatusWrongType);
  if (i.value < 0 || i.value >= vm.program_size) {
    if constexpr (D) return status(kStatusInvalidValue);
    Internal::jump_ok(vm, i.value);  // faults: a vector outside the program
    return ok();
  }
  vm.vectors[i.type] = i.value;
  return done<D>(vm, kStatusOk);
}
template <bool D> R op_RETI(Vm& vm, const Instruction& i) {
  TMCL_FLOW_IN_DIRECT(i);
  if (!vm.in_handler) {  // E13: RETI outside a handler is ignored
    if constexpr (!D)
      if (Internal::warn(vm, RuntimeWarning::RetiOutsideHandler, "RETI while no interrupt is being served"))
        return ok();
    return done<D>(vm, kStatusOk);
  }
  vm.pc = vm.saved.pc;
  vm.acc = vm.saved.acc;
  vm.x = vm.saved.x;
  vm.flags = vm.saved.flags;
  vm.wait = vm.saved.wait;
  vm.sp = vm.saved.stack_depth;  // frames the handler left behind are dropped
  vm.in_handler = false;
  Internal::recheck(vm);
  return ok();  // the traced run loop reports leaving the handler
}
// SAC (TMCM-351 manual, 4.6.24): TYPE the chip select (0, 2, 3; +128 sends the accumulator
// instead of VALUE), MOTOR the number of bytes (1 to 4). No SPI device is attached to the
// virtual module: the bus reads back 0, into the accumulator (docs/errata.md).
template <bool D> R op_SAC(Vm& vm, const Instruction& i) {
  const int select = i.type & 127;
  if (select != 0 && select != 2 && select != 3) return done<D>(vm, kStatusWrongType);
  if (i.motor < 1 || i.motor > 4) return done<D>(vm, kStatusInvalidValue);
  return load<D>(vm, kStatusOk, 0);
}
template <bool D> R op_CLE(Vm& vm, const Instruction& i) {
  // By CLE's keyword: ALL, ETO, EAL, EDV, EPO, ESD.
  static constexpr std::uint8_t kMask[] = {0x1F, kErrTimeout, kErrAlarm, kErrDeviation, kErrPosition, kErrShutdown};
  static_assert(kw::Cle::ALL == 0 && kw::Cle::ETO == 1 && kw::Cle::EAL == 2 && kw::Cle::EDV == 3 && kw::Cle::EPO == 4 &&
                kw::Cle::ESD == 5);
  if (i.type > kw::Cle::ESD) return done<D>(vm, kStatusWrongType);
  vm.errors = static_cast<std::uint8_t>(vm.errors & ~kMask[i.type]);
  return done<D>(vm, kStatusOk);
}

// ---------------------------------------------------------------- user functions
// E15: a virtual module has no customer firmware extensions.
template <bool D> R user_function(Vm& vm, const Instruction& i) {
  if constexpr (D) return status(kStatusNotAvailable);
  Internal::fault(vm, "UF" + std::to_string(i.op - 64) + " (a customer-specific user function) has no implementation in the virtual module, at " +
           vm.where(vm.pc));
  return ok();
}
template <bool D> R op_UF0(Vm& vm, const Instruction& i) { return user_function<D>(vm, i); }
template <bool D> R op_UF1(Vm& vm, const Instruction& i) { return user_function<D>(vm, i); }
template <bool D> R op_UF2(Vm& vm, const Instruction& i) { return user_function<D>(vm, i); }
template <bool D> R op_UF3(Vm& vm, const Instruction& i) { return user_function<D>(vm, i); }
template <bool D> R op_UF4(Vm& vm, const Instruction& i) { return user_function<D>(vm, i); }
template <bool D> R op_UF5(Vm& vm, const Instruction& i) { return user_function<D>(vm, i); }
template <bool D> R op_UF6(Vm& vm, const Instruction& i) { return user_function<D>(vm, i); }
template <bool D> R op_UF7(Vm& vm, const Instruction& i) { return user_function<D>(vm, i); }

#undef TMCL_FLOW_IN_DIRECT

// The dispatch: one case per row of the instruction table.
template <bool kDirect>
inline R dispatch(Vm& vm, const Instruction& ins, bool& known) {
  known = true;
  switch (static_cast<Op>(ins.op)) {
#define TMCL_OP(code, id, ...) \
  case Op::id: return op_##id<kDirect>(vm, ins);
#define TMCL_CTL(code, id, meaning)
#include "tmcl/opcodes.def"
#undef TMCL_OP
#undef TMCL_CTL
    default: break;
  }
  known = false;
  return status(kStatusInvalidCommand);
}

}  // namespace tmcl::ops
