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
      {"hardstop left 0 at -5\nhardstop left 0 at -9", "s.txt:2:10: error: hardstop left 0 is already placed at line 1"},
      // Geometry (issue 41, 4): the carriage starts at 0, between its ends.
      {"hardstop left 0 at 5", "s.txt:1:20: error: the carriage starts at position 0, beyond this left end (a left end lies at or below 0)"},
      {"hardstop right 0 at -1", "s.txt:1:21: error: the carriage starts at position 0, beyond this right end (a right end lies at or above 0)"},
      {"hardstop left 0 at -50\nhardstop right 0 at -100", "s.txt:2:21: error: the right end lies left of the left end at -50 (line 1)"},
      {"hardstop right 0 at 50\nhardstop left 0 at 100", "s.txt:2:20: error: the left end lies right of the right end at 50 (line 1)"},
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

// A stall homing the TMCM-1260 runs in StealthChop (186 above the search speed, 187 > 0): the
// module measures no stallGuard2 load there, so its stop on stall never comes (errata E78). The
// run says so once, as a note; under --strict the note is a warning, and so a fault.
TEST(stall_relied_on_in_stealthchop_is_a_note) {
  for (int strict = 0; strict < 2; ++strict) {
    World w("tmc5160", *tmcl::find_profile("tmcm-1260"),
            {I(Op::SAP, 181, 0, 1), I(Op::SAP, 186, 0, 100000), I(Op::SAP, 187, 0, 5), I(Op::ROR, 0, 0, 51200),
             I(Op::WAIT, 0, 0, 300), I(Op::STOP)},
            "hardstop right 0 at 20000\n");
    w.vm.strict = strict != 0;
    auto r = w.vm.run({100000, tmcl::kNever});
    if (strict) {
      CHECK(r.halt == Halt::Fault);
      CHECK(r.message.find("StealthChop") != std::string::npos);
      continue;
    }
    CHECK(r.halt == Halt::Stop);
    CHECK_EQ(w.vm.notes.size(), std::size_t{1});
    CHECK_EQ(w.vm.notes[0].message,
             std::string("motor 0 met a hard stop or a load with stop on stall (181) on, but in StealthChop (187 > 0, "
                         "below 186) stallGuard2 measures nothing: no stall stops it, steps are lost (errata E78)"));
    CHECK(w.core->get_param(0, 3) > 0);  // no stall stopped it
  }
}

// A WAIT POS after the motor stopped by itself (issue 41, 4): the blocked run says why, with the
// target kept: a stop on stall at a hard stop, an encoder deviation beyond 212.
TEST(wait_pos_after_a_stop_on_stall_or_deviation_says_why) {
  {
    World w("tmc5160", *tmcl::find_profile("tmcm-1260"),
            {I(Op::SAP, 140, 0, 8), I(Op::SAP, 181, 0, 1), I(Op::MVP, 0, 0, 250000), I(Op::WAIT, 1, 0, 0), I(Op::STOP)},
            "hardstop right 0 at 120000\n");
    auto r = w.vm.run({100000, tmcl::kNever});
    CHECK(r.halt == Halt::Blocked);
    const std::string at = std::to_string(w.core->position(0));
    CHECK(r.message.find("can never end: motor 0 stopped on stall (stop on stall, 181) at position " + at +
                         "; its target 250000 is kept, and no timer, motion, input or timeout is pending") != std::string::npos);
  }
  {
    World w("tmc5160", *tmcl::find_profile("tmcm-1260"),
            {I(Op::SAP, 212, 0, 300), I(Op::MVP, 0, 0, 250000), I(Op::WAIT, 1, 0, 0), I(Op::STOP)},
            "hardstop right 0 at 120000\n");
    auto r = w.vm.run({100000, tmcl::kNever});
    CHECK(r.halt == Halt::Blocked);
    CHECK(r.message.find("can never end: motor 0 stopped on an encoder deviation beyond 212 at position 120301; its "
                         "target 250000 is kept") != std::string::npos);
  }
}
