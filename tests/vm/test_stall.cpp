// Loads, hard stops and stalls (issue 34): the scenario's `hardstop` and `load` lines and their
// errors, and what the VM makes of a stall: the stall interrupt (15 + motor), the load value and
// the stall flags as a program reads them, lost steps at a hard stop. The model itself is tested
// through the core API in tests/motion/test_stall.cpp.
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

TEST(scenario_hardstop_and_load_lines) {
  std::vector<InputEvent> ev;
  std::string err;
  CHECK(tmcl::parse_scenario("hardstop left 0 at -21000\nhardstop right 0 at 31000  # end\n"
                             "switch left 0 at -20000\nhardstop left 1 at -20010\n"
                             "at 4s load 0 = 60%\nat 5s load 0 = 0%\nload 1 from 5000 to 6000 = 150%\n",
                             "s.txt", ev, err));
  CHECK_EQ(err, std::string());
  CHECK_EQ(ev.size(), std::size_t{7});
  CHECK(ev[0].kind == InputEvent::HardStop && ev[0].input == SwitchInput::StopLeft && ev[0].from == -21000);
  CHECK(ev[1].kind == InputEvent::HardStop && ev[1].input == SwitchInput::StopRight && ev[1].from == 31000);
  CHECK(ev[3].kind == InputEvent::HardStop && ev[3].index == 1);  // inside switch left 0's range: allowed
  CHECK(ev[4].kind == InputEvent::Load && ev[4].at == 4'000'000 && ev[4].value == 60 && ev[4].index == 0);
  CHECK(ev[5].kind == InputEvent::Load && ev[5].value == 0);
  CHECK(ev[6].kind == InputEvent::LoadZone && ev[6].from == 5000 && ev[6].to == 6000 && ev[6].value == 150);
  CHECK(ev[0].placed_kind() && ev[6].placed_kind() && !ev[4].placed_kind());
}

TEST(scenario_hardstop_and_load_errors) {
  const ScenarioError cases[] = {
      {"hardstop up 0 at 5", "s.txt:1:10: error: unknown hard stop 'up' (left, right)"},
      {"hardstop rihgt 0 at 5", "s.txt:1:10: error: unknown hard stop 'rihgt' (left, right); did you mean 'right'?"},
      {"hardstop left 3 at 5", "s.txt:1:15: error: tmcm-1110 has no motor 3 (0..2)"},
      {"hardstop left 0 at x", "s.txt:1:20: error: bad position 'x' (microsteps, a 32-bit integer)"},
      {"hardstop left 0 near 5", "s.txt:1:17: error: expected 'hardstop left|right MOTOR at POSITION': 'at' expected here"},
      {"hardstop left 0", "s.txt:1:16: error: expected 'hardstop left|right MOTOR at POSITION': the line ends early"},
      {"hardstop left 0 at 5 6", "s.txt:1:22: error: unexpected '6' after the position"},
      {"hardstop left 0 at 5\nhardstop left 0 at 9", "s.txt:2:10: error: hardstop left 0 is already placed at line 1"},
      {"at 1s load 0 = 50", "s.txt:1:16: error: bad load '50' (a percentage needs its '%': 50%)"},
      {"at 1s load 0 = -5%", "s.txt:1:16: error: bad load '-5%' (0%..1000%)"},
      {"at 1s load 0 = 1001%", "s.txt:1:16: error: bad load '1001%' (0%..1000%)"},
      {"at 1s load 0 = x%", "s.txt:1:16: error: bad load 'x%' (0%..1000%)"},
      {"at 1s load 7 = 5%", "s.txt:1:12: error: tmcm-1110 has no motor 7 (0..2)"},
      {"at 1s lood 0 = 5%", "s.txt:1:7: error: unknown input 'lood' (input, analog, left, right, home, slip, load); did you mean 'load'?"},
      {"load 0 from 1 to 2 = 5", "s.txt:1:22: error: bad load '5' (a percentage needs its '%': 50%)"},
      {"load 0 from 1 to 2 = 20.5%", "s.txt:1:22: error: bad load '20.5%' (0%..1000%)"},
      {"load 5 from 1 to 2 = 5%", "s.txt:1:6: error: tmcm-1110 has no motor 5 (0..2)"},
      {"load 0 from 9 to 2 = 5%", "s.txt:1:18: error: the range ends below its start (9 > 2)"},
      {"load 0 at 9 = 5%", "s.txt:1:17: error: expected 'load MOTOR from POSITION to POSITION = P%'"},
      {"load 0 from 1 until 2 = 5%", "s.txt:1:15: error: 'to' expected here"},
      {"load 0 from 1 to 2 is 5%", "s.txt:1:20: error: '=' expected here"},
      {"load 0 from 1 to 2 = 5% 6", "s.txt:1:25: error: unexpected '6' after the load"},
  };
  tmcl::ScenarioOptions opts;
  opts.motors = 3;
  opts.module = "tmcm-1110";
  expect_scenario_errors(cases, opts);
}

// The TMCM-351's stallGuard (errata E75) as a program meets it: motor 2 runs into its hard stop
// with stall detection on (205), stops, and raises its own stall vector 17 (15 + motor) once;
// 207 bit 1 is set on that motor only.
TEST(sg1_stall_raises_the_vector_of_its_motor) {
  World w("tmc429", *tmcl::find_profile("tmcm-351"),
          {I(Op::VECT, 17, 0, 7), I(Op::EI, 17), I(Op::EI, 255), I(Op::SAP, 205, 2, 5), I(Op::ROL, 0, 2, 500),
           I(Op::WAIT, 0, 0, 100), I(Op::STOP), I(Op::GGP, 17, 2), I(Op::CALC, 0, 0, 1), I(Op::AGP, 17, 2),
           I(Op::RETI)},
          "hardstop left 2 at -3000\n");
  auto r = w.vm.run({100000, tmcl::kNever});
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(w.vm.vars[17], 1);
  CHECK_EQ(w.core->get_param(2, 3), 0);
  CHECK_EQ(w.core->get_param(2, 207), 2);
  CHECK_EQ(w.core->get_param(0, 207), 0);
  CHECK_EQ(w.core->get_param(2, 206), 7);
  CHECK(w.core->position(2) <= -3000 && w.core->position(2) >= -3000 - 16 - 1);
}
