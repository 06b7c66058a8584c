// Test helpers for the VM unit tests: programs written as C++ instruction lists, a machine with
// the ideal motion core, and a small test profile with access rules and ranges.
#pragma once

#include <memory>
#include <vector>

#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"
#include "tmcl/vm.hpp"

namespace vmtest {

using tmcl::Instruction;
using tmcl::Op;

inline Instruction I(Op op, int type = 0, int motor = 0, std::int32_t value = 0) {
  return Instruction{static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), value};
}

// A profile with real access rules, for the tests that need them (the built-in tables are data
// maintained elsewhere; these tests pin the VM's rules, not the tables).
inline const tmcl::Profile& test_profile() {
  using namespace tmcl;
  static const ParamInfo axis[] = {
      {0, "target", INT32_MIN, INT32_MAX, kRead | kWrite, 0, ""},
      {1, "actual", INT32_MIN, INT32_MAX, kRead | kWrite, 0, ""},
      {2, "target speed", -1000000, 1000000, kRead | kWrite, 0, ""},
      {3, "actual speed", -1000000, 1000000, kRead, 0, ""},
      {4, "max speed", 0, 1000000, kRead | kWrite | kEeprom, 1000, ""},
      {8, "reached", 0, 1, kRead, 0, ""},
      {127, "rel option", 0, 2, kRead | kWrite, 0, ""},
      {140, "microsteps", 0, 8, kRead | kWrite | kEeprom, 8, ""},
      {209, "encoder", INT32_MIN, INT32_MAX, kRead | kWrite, 0, ""},
      {212, "max deviation", 0, INT32_MAX, kRead | kWrite, 0, ""},
  };
  static const ParamInfo bank0[] = {
      {77, "autostart", 0, 1, kRead | kWrite | kAutoStore, 0, ""},
      {84, "coords in eeprom", 0, 1, kRead | kWrite | kAutoStore, 0, ""},
      {85, "do not restore vars", 0, 1, kRead | kWrite | kAutoStore, 0, ""},
      {128, "status", 0, 3, kRead, 0, ""},
      {130, "pc", 0, 0, kRead, 0, ""},
      {132, "tick", 0, INT32_MAX, kRead | kWrite, 0, ""},
      {133, "random", 0, INT32_MAX, kRead | kWrite, 0, ""},
  };
  static const ParamInfo bank3[] = {
      {0, "timer 0", 0, 4294967295LL, kRead | kWrite, 0, ""}, {1, "timer 1", 0, 4294967295LL, kRead | kWrite, 0, ""},
      {2, "timer 2", 0, 4294967295LL, kRead | kWrite, 0, ""}, {27, "left 0", 0, 3, kRead | kWrite, 0, ""},
      {28, "right 0", 0, 3, kRead | kWrite, 0, ""},
  };
  static const InterruptVector vectors[] = {
      {0, "TI_TIMER0", ""}, {1, "TI_TIMER1", ""}, {2, "TI_TIMER2", ""}, {3, "TI_TARGET0", ""},
      {21, "TI_DEVIATION0", ""}, {27, "TI_STOPL0", ""}, {28, "TI_STOPR0", ""},
  };
  static const Profile p = [] {
    Profile q{};
    q.name = "test";
    q.title = "test profile";
    for (const auto& op : all_ops()) q.commands.set(op.code);
    q.commands.reset(static_cast<std::size_t>(Op::UF0));  // one unavailable command
    q.any_parameter = false;
    q.axis_params = axis;
    q.bank0 = bank0;
    q.bank3 = bank3;
    q.user_vars = 256;
    q.eeprom_user_vars = 56;
    q.coords = 21;
    q.vectors = vectors;
    q.any_port = true;  // every port 0..15, as E18 had it
    q.program_memory = 2048;
    q.motors = 1;
    q.default_motion = "ideal";
    q.firmware = "0000V100";
    return q;
  }();
  return p;
}

// A trace that prints nothing: a VM with it set runs the traced loop (every instruction through
// the table dispatch), to compare with the fast path.
struct NullTrace final : tmcl::TraceSink {
  void instruction(const tmcl::Vm&, tmcl::SimTime, std::int32_t, const Instruction&) override {}
  void interrupt_enter(const tmcl::Vm&, int, std::int32_t) override {}
  void interrupt_leave(const tmcl::Vm&, std::int32_t) override {}
  void motion_event(const tmcl::Vm&, const tmcl::MotionEvent&) override {}
  void wait_end(const tmcl::Vm&, std::int32_t, bool) override {}
  void input_event(const tmcl::Vm&, const std::string&) override {}
};

struct Machine {
  std::unique_ptr<tmcl::MotionCore> core = tmcl::make_ideal_motion_core();
  tmcl::Vm vm;
  explicit Machine(const std::vector<Instruction>& prog, const tmcl::Profile& p = test_profile(), tmcl::SimTime instr = 0)
      : vm(p, *core) {
    vm.instr_time = instr;
    vm.load(prog);
    vm.power_on(nullptr);
    vm.start(0);
  }
  tmcl::RunResult run(tmcl::Limits l = {}) {
    if (l.max_steps == UINT64_MAX) l.max_steps = 1'000'000;
    return vm.run(l);
  }
};

}  // namespace vmtest
