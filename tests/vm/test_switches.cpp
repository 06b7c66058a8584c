// Switches placed at positions (scenario `switch left 0 at -20000`): the scenario lines and their
// errors, and what the VM makes of the core's switch events: the program's switch state, WAIT
// LIMSW, the stop-switch interrupts, timed lines mixed in, and a core that cannot place switches.
#include <string>

#include "check.hpp"
#include "machine.hpp"
#include "scenario_world.hpp"
#include "tmcl/scenario.hpp"

using namespace vmtest;
using tmcl::Halt;
using tmcl::InputEvent;
using tmcl::Op;
using tmcl::SwitchInput;


TEST(scenario_switch_lines) {
  std::vector<InputEvent> ev;
  std::string err;
  CHECK(tmcl::parse_scenario("switch left 0 at -20000\nswitch right 1 at 30000  # end\n"
                             "switch home 0 from -150 to 150\nswitch left 2 from -5 to 5\nat 1s left 0 = 1\n",
                             "s.txt", ev, err));
  CHECK_EQ(ev.size(), 5u);
  CHECK(ev[0].kind == InputEvent::Placed && ev[0].input == SwitchInput::StopLeft);
  CHECK(ev[0].from == INT64_MIN && ev[0].to == -20000 && ev[0].at == 0);
  CHECK(ev[1].input == SwitchInput::StopRight && ev[1].index == 1 && ev[1].from == 30000 && ev[1].to == INT64_MAX);
  CHECK(ev[2].input == SwitchInput::Home && ev[2].from == -150 && ev[2].to == 150 && ev[2].line == 3);
  CHECK(ev[3].input == SwitchInput::StopLeft && ev[3].index == 2 && ev[3].from == -5 && ev[3].to == 5);
  CHECK(ev[4].kind == InputEvent::StopLeft);
}

TEST(scenario_switch_line_errors) {
  const ScenarioError cases[] = {
      {"switch home 0 at 5", "s.txt:1:15: error: a home switch closes over a range"},
      {"switch lfet 0 at 5", "s.txt:1:8: error: unknown switch 'lfet' (left, right, home); did you mean 'left'?"},
      {"switch left 0 from 5 to 1", "s.txt:1:25: error: the range ends below its start (5 > 1)"},
      {"switch left 0 from 5 until 9", "s.txt:1:22: error: 'to' expected here"},
      {"switch left 0 from 5", "s.txt:1:21: error: 'to POSITION' is missing"},
      {"switch left 0", "s.txt:1:14: error: expected 'switch left|right MOTOR at POSITION'"},
      {"switch left 0 near 5", "s.txt:1:15: error: expected 'switch left|right MOTOR at POSITION' or"},
      {"switch left 9 at 5", "s.txt:1:13: error: usb-2-sd has no motor 9 (0..0)"},
      {"switch left 0 at 5.5", "s.txt:1:18: error: bad position '5.5' (microsteps, a 32-bit integer)"},
      {"switch left 0 at 5 6", "s.txt:1:20: error: unexpected '6' after the position"},
      {"switch home 0 from 1 to 2 3", "s.txt:1:27: error: unexpected '3' after the range"},
      {"switch left 0 at -5\nswitch left 0 from 1 to 2", "s.txt:2:8: error: switch left 0 is already placed at line 1"},
  };
  tmcl::ScenarioOptions opts;
  opts.motors = 1;
  opts.module = "usb-2-sd";
  expect_scenario_errors(cases, opts);
}

// The left switch at -2000 stops a ROL (tmc429: hard stop by default), ends WAIT LIMSW at that
// instant and raises interrupt 27 on its closing; the program reads the switch states.
TEST(placed_switch_ends_wait_limsw_and_raises_its_interrupt) {
  World w("tmc429",
          {I(Op::VECT, 27, 0, 9), I(Op::SGP, 27, 3, 3), I(Op::EI, 27), I(Op::EI, 255), I(Op::ROL, 0, 0, 1000),
           I(Op::WAIT, 3, 0, 0), I(Op::GAP, 11, 0), I(Op::STOP), I(Op::STOP), I(Op::CALCV, 0, 27, 1), I(Op::RETI)},
          "switch left 0 at -2000\n");
  auto r = w.vm.run({1000, tmcl::kNever});
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(w.vm.acc, 1);
  CHECK_EQ(w.vm.vars[27], 1);
  CHECK(w.vm.switches[0].left);
  CHECK_EQ(w.core->position(0), -2000);
  // ROL takes effect at 100 us; v = 1000 units = 30517.578 pps after v/a = 65.536 ms over 1000
  // steps, then 1000 steps more; then the handler (2 instructions), GAP and STOP.
  CHECK_EQ(w.vm.now, 100 + 65536 + 32768 + 4 * 20);
}

// A timed line and a placed switch on one input: closed while either closes it; the interrupt
// comes on the input's own transitions only.
TEST(placed_and_timed_switches_mix) {
  World w("tmc429",
          {I(Op::VECT, 27, 0, 5), I(Op::SGP, 27, 3, 3), I(Op::EI, 27), I(Op::EI, 255), I(Op::WAIT, 0, 0, 300),
           I(Op::CALCV, 0, 27, 1), I(Op::RETI)},
          "switch left 0 at -100\nat 1s left 0 = 1\nat 2s left 0 = 0\n");
  auto r = w.vm.run({100000, 3'000'000});
  CHECK(r.halt == Halt::TimeLimit);
  CHECK_EQ(w.vm.vars[27], 2);  // closed at 1 s, open at 2 s
  CHECK(!w.vm.switches[0].left);
  World v("tmc429", {I(Op::WAIT, 0, 0, 300), I(Op::STOP)}, "switch left 0 at 100\nat 1s left 0 = 1\nat 2s left 0 = 0\n");
  v.vm.run({100000, tmcl::kNever});
  CHECK(v.vm.switches[0].left);  // the motor stands in the placed switch: still closed
  CHECK(v.vm.switches[0].placed == 1 && v.vm.switches[0].timed == 0);
}

TEST(placed_switch_on_the_tmc4361_stops_there) {
  World w("tmc4361", {I(Op::MVP, 0, 0, 100000), I(Op::WAIT, 1, 0, 200), I(Op::GAP, 1, 0), I(Op::STOP)},
          "switch right 0 at 30000\n");
  w.vm.run({1000, tmcl::kNever});
  CHECK_EQ(w.vm.acc, 30000);  // DSTOP 0: a hard stop on the switch; the target is never reached
  CHECK(w.vm.switches[0].right);
  CHECK(w.vm.errors & tmcl::kErrTimeout);
}

TEST(a_core_without_placed_switches_is_a_fault) {
  World w("ideal", {I(Op::STOP)}, "\n\nswitch home 0 from 1 to 2\n");
  auto r = w.vm.run({1000, tmcl::kNever});
  CHECK(r.halt == Halt::Fault);
  CHECK_EQ(r.message, std::string("the motion core 'ideal' cannot place switches at positions (scenario line 3)"));
}

// A search that never meets its switch runs until a WAIT RFS timeout (ETO) or RFS STOP; RFS
// STATUS reads 1 while it runs, 0 after.
TEST(wait_rfs_on_a_search_that_finds_nothing) {
  World w("tmc429",
          {I(Op::RFS, 0, 0), I(Op::WAIT, 4, 0, 100), I(Op::RFS, 2, 0), I(Op::CALCX, 10), I(Op::RFS, 1, 0),
           I(Op::WAIT, 4, 0, 0), I(Op::RFS, 2, 0), I(Op::STOP)},
          "");
  auto r = w.vm.run({1000, tmcl::kNever});
  CHECK(r.halt == Halt::Stop);
  CHECK(w.vm.errors & tmcl::kErrTimeout);
  CHECK_EQ(w.vm.x, 1);    // STATUS after the timeout: still searching
  CHECK_EQ(w.vm.acc, 0);  // after RFS STOP: no search
  World v("tmc429", {I(Op::RFS, 0, 0), I(Op::WAIT, 4, 0, 0), I(Op::STOP)}, "");
  auto b = v.vm.run({1000, tmcl::kNever});
  CHECK(b.halt == Halt::Blocked);
  CHECK(b.message.find("WAIT RFS") != std::string::npos);
}

// Placed switches belong to the machine: they work in direct mode with no program running (a
// host driving the virtual module), and again after a power cycle.
TEST(placed_switches_in_direct_mode_and_after_power_on) {
  World w("tmc429", {I(Op::STOP)}, "switch left 0 at -2000\n");
  w.vm.stop_application();
  for (int cycle = 0; cycle < 2; ++cycle) {
    CHECK_EQ(w.vm.execute_direct(I(Op::ROL, 0, 0, 1000)).status, tmcl::kStatusOk);
    auto r = w.vm.run({UINT64_MAX, 1'000'000});
    CHECK(r.halt == Halt::NotRunning);
    CHECK_EQ(w.core->position(0), -2000);  // stopped on the switch
    CHECK(w.vm.switches[0].left);
    w.vm.power_on(nullptr);
    CHECK(!w.vm.switches[0].left);
    CHECK_EQ(w.core->position(0), 0);
  }
}
