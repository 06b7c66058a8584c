// The encoder as a program meets it (issue 34): a scenario's slip on a TMCM core stops the motor
// beyond 212 and raises the deviation interrupt 21 + motor with the EDV error flag; a slip line on
// a core that models no encoder is a file error naming the core (line and column), and a VM
// whose scenario was not checked against its core faults at the slip, never silently.
#include <string>

#include "check.hpp"
#include "machine.hpp"
#include "scenario_world.hpp"
#include "tmcl/scenario.hpp"

using namespace vmtest;
using tmcl::Halt;
using tmcl::InputEvent;
using tmcl::Op;


TEST(slip_beyond_212_raises_the_deviation_interrupt) {
  World w("tmc429", tmcl::generic_profile(),
             {I(Op::VECT, 21, 0, 7), I(Op::EI, 21), I(Op::EI, 255), I(Op::SAP, 212, 0, 1000), I(Op::ROR, 0, 0, 500),
              I(Op::WAIT, 0, 0, 300), I(Op::STOP), I(Op::CALCV, 0, 21, 1), I(Op::RETI)},
             "at 1s slip 0 = -900\nat 2s slip 0 = -200\n");
  auto r = w.vm.run({100000, tmcl::kNever});
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(w.vm.vars[21], 1);  // once, at 2 s: 900 was within 212
  CHECK(w.vm.errors & tmcl::kErrDeviation);
  CHECK_EQ(w.core->get_param(0, 3), 0);
  CHECK_EQ(w.core->get_param(0, 207), 2);
  CHECK_EQ(w.core->get_param(0, 209), w.core->position(0) - 1100);
}

TEST(slip_on_a_core_without_encoder_is_a_file_error) {
  tmcl::ScenarioOptions o;
  o.motors = 1;
  o.module = "tmc2300-eval";
  o.no_encoder = "linear";
  std::vector<InputEvent> ev;
  std::string err;
  CHECK(!tmcl::parse_scenario("at 1s input 0 = 1\nat 2s  slip 0 = -400\n", "s.txt", ev, err, o));
  CHECK_EQ(err, std::string("s.txt:2:8: error: 'slip' needs an encoder: the motion core 'linear' models none on "
                            "tmc2300-eval\n at 2s  slip 0 = -400\n        ^~~~\n"));
  o.no_encoder.clear();  // the same line where the core has one
  CHECK(tmcl::parse_scenario("at 2s slip 0 = -400\n", "s.txt", ev, err, o));
}

TEST(unchecked_slip_on_a_core_without_encoder_faults) {
  World w("linear", *tmcl::find_profile("tmc2300-eval"), {I(Op::WAIT, 0, 0, 300), I(Op::STOP)},
             "\nat 1s slip 0 = -400\n");
  auto r = w.vm.run({100000, tmcl::kNever});
  CHECK(r.halt == Halt::Fault);
  CHECK_EQ(r.message, std::string("the motion core 'linear' models no encoder on tmc2300-eval to slip (scenario line 2)"));
}

// The PD60-1260 lost-step routine of issue 41 (1): 212 = 300, no stop on stall, a right hard stop
// at 120000, MVP ABS 250000. The counter parts from the shaft at the end: the motor stops at the
// first step beyond 212 (120301), 207 has its deviation bit, and the program's deviation handler
// (vector 21) runs once.
TEST(lost_steps_at_a_hard_stop_raise_the_deviation_interrupt_once) {
  World w("tmc5160", *tmcl::find_profile("tmcm-1260"),
          {I(Op::VECT, 21, 0, 10), I(Op::EI, 21), I(Op::EI, 255), I(Op::SAP, 212, 0, 300), I(Op::SAP, 181, 0, 0),
           I(Op::SAP, 12, 0, 1), I(Op::MVP, 0, 0, 250000), I(Op::WAIT, 0, 0, 1000), I(Op::GAP, 207, 0),
           I(Op::STOP), I(Op::GGP, 21, 2), I(Op::CALC, 0, 0, 1), I(Op::AGP, 21, 2), I(Op::RETI)},  // no CALCV here
          "hardstop right 0 at 120000\n");
  auto r = w.vm.run({100000, tmcl::kNever});
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(w.vm.vars[21], 1);
  CHECK(w.vm.errors & tmcl::kErrDeviation);
  CHECK_EQ(w.core->position(0), 120301);
  CHECK_EQ(w.core->get_param(0, 209), 120000);
  CHECK_EQ(w.vm.acc & 2, 2);  // 207 as the program read it: '2 deviation error'
  CHECK_EQ(w.core->get_param(0, 3), 0);
}
