// WAIT: ticks, position, switches and reference search, timeouts that set ETO, the -1 form,
// time jumps instead of busy loops, and blocking forever (docs/errata.md E7, E22).
#include "check.hpp"
#include "machine.hpp"

using namespace vmtest;
using tmcl::Halt;
using tmcl::InputEvent;
using tmcl::Op;

TEST(wait_ticks_exact_time) {
  Machine m({I(Op::WAIT, 0, 0, 50), I(Op::STOP)}, test_profile(), 20);
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.now, 500'000 + 20);  // WAIT starts at 0, lasts 50 ticks; STOP takes 20 us
  CHECK_EQ(m.vm.steps, 2u);
}

TEST(wait_ticks_minus_one_takes_accumulator) {  // E7
  Machine m({I(Op::CALC, 9, 0, 3), I(Op::WAIT, 0, 0, -1), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.now, 30'000);
  Machine n({I(Op::CALC, 9, 0, -7), I(Op::WAIT, 0, 0, -1), I(Op::STOP)});
  n.run();
  CHECK_EQ(n.vm.now, 0);  // negative accumulator: no wait
}

TEST(wait_an_hour_is_instant) {
  Machine m({I(Op::WAIT, 0, 0, 360000), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.now, 3600LL * 1'000'000);
}

TEST(wait_pos_reached_at_once_with_ideal_core) {
  Machine m({I(Op::MVP, 0, 0, 51200), I(Op::WAIT, 1, 0, 0), I(Op::GAP, 1, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.acc, 51200);
  CHECK_EQ(m.vm.errors, 0);
}

TEST(wait_pos_timeout_sets_eto) {
  // rotating: the target is never reached; timeout after 5 ticks
  Machine m({I(Op::ROR, 0, 0, 1000), I(Op::WAIT, 1, 0, 5), I(Op::JC, 8, 0, 4), I(Op::STOP), I(Op::CALC, 9, 0, 1),
             I(Op::CLE, 1), I(Op::STOP)});
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.acc, 1);
  CHECK_EQ(m.vm.errors, 0);
  CHECK_EQ(m.vm.now, 50'000);
}

TEST(wait_pos_without_timeout_blocks) {  // E22
  Machine m({I(Op::ROR, 0, 0, 1000), I(Op::WAIT, 1, 0, 0), I(Op::STOP)});
  auto r = m.run();
  CHECK(r.halt == Halt::Blocked);
  CHECK(r.message.find("WAIT POS") != std::string::npos);
  Machine n({I(Op::ROR, 0, 0, 1000), I(Op::WAIT, 1, 0, 0), I(Op::STOP)});
  auto t = n.run({UINT64_MAX, 2'000'000});
  CHECK(t.halt == Halt::TimeLimit);
  CHECK_EQ(n.vm.now, 2'000'000);
  CHECK_EQ(n.vm.axis_param(0, 1), 2000);  // 1000 pps for 2 s
}

TEST(wait_limsw_and_refsw_from_inputs) {
  Machine m({I(Op::WAIT, 3, 0, 0), I(Op::GGP, 132, 0), I(Op::WAIT, 2, 0, 100), I(Op::STOP)});
  InputEvent left;
  left.at = 1'234'000;
  left.kind = InputEvent::StopLeft;
  left.value = 1;
  InputEvent home;
  home.at = 1'500'000;
  home.kind = InputEvent::Home;
  home.value = 1;
  m.vm.add_inputs({left, home});
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.acc, 1234);
  CHECK_EQ(m.vm.now, 1'500'000);
  CHECK_EQ(m.vm.errors, 0);
}

TEST(wait_refsw_timeout) {
  Machine m({I(Op::WAIT, 2, 0, 10), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.errors, tmcl::kErrTimeout);
  CHECK_EQ(m.vm.now, 100'000);
}

TEST(wait_rfs) {
  Machine m({I(Op::MVP, 0, 0, 500), I(Op::RFS, 0, 0), I(Op::WAIT, 4, 0, 0), I(Op::RFS, 2, 0), I(Op::GAP, 1, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.acc, 0);  // ideal reference search: home is where the motor is, position 0
}

TEST(wait_bad_type_or_motor_ignored) {
  Machine m({I(Op::WAIT, 9, 0, 100), I(Op::WAIT, 1, 5, 100), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.now, 0);
  CHECK_EQ(m.vm.pc, 2);
}

TEST(tick_timer_counts_ms_and_is_writable) {
  Machine m({I(Op::WAIT, 0, 0, 12), I(Op::GGP, 132, 0), I(Op::CALCX, 9), I(Op::SGP, 132, 0, 1000), I(Op::WAIT, 0, 0, 1),
             I(Op::GGP, 132, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.x, 120);
  CHECK_EQ(m.vm.acc, 1010);
}

namespace {
// A broken core: always announces an event at instant 5 and never gets past it.
class StuckCore final : public tmcl::MotionCore {
 public:
  std::string_view name() const override { return "stuck"; }
  void reset(const tmcl::Profile&, int) override {}
  tmcl::SimTime next_event() const override { return 5; }
  void advance(tmcl::SimTime, std::vector<tmcl::MotionEvent>&) override {}
  bool owns(int) const override { return false; }
  tmcl::ParamWrite set_param(int, int, std::int32_t) override { return tmcl::ParamWrite::Ok; }
  std::int32_t get_param(int, int) override { return 0; }
  void move_absolute(int, std::int32_t) override {}
  void move_relative(int, std::int32_t) override {}
  void rotate(int, std::int32_t) override {}
  void stop(int) override {}
  std::int32_t reference_search(int, tmcl::RfsAction) override { return 0; }
  void set_switch(int, tmcl::SwitchInput, bool) override {}
  void encoder_slip(int, std::int32_t) override {}
  std::int32_t position(int) const override { return 0; }
  bool target_reached(int) const override { return false; }
  bool reference_done(int) const override { return false; }
};
}  // namespace

TEST(a_stuck_motion_core_is_a_fault_not_a_hang) {
  StuckCore core;
  tmcl::Vm vm(test_profile(), core);
  vm.load({I(Op::WAIT, 1, 0, 0), I(Op::STOP)});
  vm.power_on(nullptr);
  vm.start(0);
  auto r = vm.run({});
  CHECK(r.halt == Halt::Fault);
  CHECK(r.message.find("motion core 'stuck'") != std::string::npos);
}
