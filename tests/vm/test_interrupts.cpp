// Interrupts: timers from bank 3, priority, no nesting, context save/restore, service during a
// WAIT that then goes on, target-reached, stop-switch and deviation interrupts, RSUB/RETI edge
// cases (docs/errata.md E6, E10, E13, E23).
#include "check.hpp"
#include "machine.hpp"

using namespace vmtest;
using tmcl::Halt;
using tmcl::InputEvent;
using tmcl::Op;

namespace {
InputEvent input(tmcl::SimTime at, InputEvent::Kind kind, int index, std::int32_t value) {
  InputEvent e;
  e.at = at;
  e.kind = kind;
  e.index = index;
  e.value = value;
  return e;
}
}  // namespace

TEST(timer_interrupt_during_wait) {
  // main: 1 s wait; timer 0 every 100 ms counts in var 0. The WAIT still ends at 1 s.
  Machine m({I(Op::VECT, 0, 0, 7), I(Op::SGP, 0, 3, 100), I(Op::EI, 0), I(Op::EI, 255), I(Op::WAIT, 0, 0, 100),
             I(Op::GGP, 132, 0), I(Op::STOP), I(Op::CALCV, 0, 0, 1), I(Op::RETI)});
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.vars[0], 10);  // at 100, 200, ..., 1000 ms: the one at 1000 ms comes first
  CHECK_EQ(m.vm.acc, 1000);
}

TEST(context_saved_and_restored) {
  Machine m({I(Op::VECT, 0, 0, 9), I(Op::SGP, 0, 3, 1), I(Op::EI, 0), I(Op::CALC, 9, 0, 5), I(Op::CALCX, 9),
             I(Op::COMP, 0, 0, 9), I(Op::EI, 255), I(Op::WAIT, 0, 0, 1), I(Op::STOP),
             // handler: clobber acc, X, flags
             I(Op::CALC, 9, 0, 0), I(Op::CALCX, 9), I(Op::CALCV, 9, 1, 1), I(Op::RETI)});
  m.run();
  CHECK_EQ(m.vm.acc, 5);
  CHECK_EQ(m.vm.x, 5);
  CHECK_EQ(m.vm.flags, tmcl::kFlagLower);
  CHECK_EQ(m.vm.vars[1], 1);
}

TEST(priority_lower_number_first_and_no_nesting) {
  // Timers 0 and 1 both due at 10 ms: 0 runs first, 1 is served after its RETI.
  // Each handler appends its number to var 10 (v10 = v10 * 10 + n + 1).
  Machine m({I(Op::VECT, 0, 0, 9), I(Op::VECT, 1, 0, 13), I(Op::SGP, 1, 3, 10), I(Op::SGP, 0, 3, 10), I(Op::EI, 0),
             I(Op::EI, 1), I(Op::EI, 255), I(Op::WAIT, 0, 0, 1), I(Op::STOP),
             I(Op::CALCV, 2, 10, 10), I(Op::CALCV, 0, 10, 1), I(Op::CALCV, 0, 11, 0), I(Op::RETI),
             I(Op::CALCV, 2, 10, 10), I(Op::CALCV, 0, 10, 2), I(Op::RETI)});
  m.run();
  CHECK_EQ(m.vm.vars[10], 12);  // timer 0 first, then timer 1 after its RETI
}

TEST(disabled_interrupts_do_not_latch) {  // E10
  Machine m({I(Op::VECT, 0, 0, 6), I(Op::SGP, 0, 3, 10), I(Op::EI, 255), I(Op::WAIT, 0, 0, 5), I(Op::EI, 0),
             I(Op::STOP), I(Op::CALCV, 0, 0, 1), I(Op::RETI)});
  m.run();
  CHECK_EQ(m.vm.vars[0], 0);
}

TEST(global_disable_keeps_pending) {
  Machine m({I(Op::VECT, 0, 0, 6), I(Op::SGP, 0, 3, 10), I(Op::EI, 0), I(Op::WAIT, 0, 0, 2), I(Op::EI, 255),
             I(Op::STOP), I(Op::CALCV, 0, 0, 1), I(Op::RETI)});
  m.run();
  CHECK_EQ(m.vm.vars[0], 1);  // latched during the WAIT, served once after EI 255
}

TEST(rsub_inside_handler_cannot_return_into_main) {  // E6
  Machine m({I(Op::VECT, 0, 0, 6), I(Op::SGP, 0, 3, 15), I(Op::EI, 0), I(Op::EI, 255), I(Op::CSUB, 0, 0, 9), I(Op::STOP),
             I(Op::RSUB), I(Op::CALCV, 0, 0, 1), I(Op::RETI),
             I(Op::WAIT, 0, 0, 2), I(Op::RSUB)});
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.vars[0], 1);  // the handler's RSUB was ignored and it went on to RETI
  CHECK_EQ(m.vm.sp, 0);
}

TEST(reti_outside_handler_is_ignored) {  // E13
  Machine m({I(Op::RETI), I(Op::CALC, 9, 0, 4), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.acc, 4);
}

TEST(target_reached_interrupt) {
  Machine m({I(Op::VECT, 3, 0, 6), I(Op::EI, 3), I(Op::EI, 255), I(Op::MVP, 0, 0, 100), I(Op::WAIT, 0, 0, 1), I(Op::STOP),
             I(Op::GAP, 1, 0), I(Op::AGP, 5, 2), I(Op::RETI)});
  m.run();
  CHECK_EQ(m.vm.vars[5], 100);
}

TEST(stop_switch_interrupt_follows_transition_setting) {
  // left switch of motor 0: interrupt 27 on low->high only (bank 3 param 27 = 1)
  Machine m({I(Op::VECT, 27, 0, 6), I(Op::SGP, 27, 3, 1), I(Op::EI, 27), I(Op::EI, 255), I(Op::WAIT, 0, 0, 100), I(Op::STOP),
             I(Op::CALCV, 0, 0, 1), I(Op::RETI)});
  m.vm.add_inputs({input(100'000, InputEvent::StopLeft, 0, 1), input(200'000, InputEvent::StopLeft, 0, 0),
                   input(300'000, InputEvent::StopLeft, 0, 1)});
  m.run();
  CHECK_EQ(m.vm.vars[0], 2);
  Machine both({I(Op::VECT, 28, 0, 6), I(Op::SGP, 28, 3, 3), I(Op::EI, 28), I(Op::EI, 255), I(Op::WAIT, 0, 0, 100), I(Op::STOP),
                I(Op::CALCV, 0, 0, 1), I(Op::RETI)});
  both.vm.add_inputs({input(100'000, InputEvent::StopRight, 0, 1), input(200'000, InputEvent::StopRight, 0, 0)});
  both.run();
  CHECK_EQ(both.vm.vars[0], 2);
}

TEST(deviation_interrupt_and_edv) {
  Machine m({I(Op::SAP, 212, 0, 100), I(Op::VECT, 21, 0, 8), I(Op::EI, 21), I(Op::EI, 255), I(Op::ROR, 0, 0, 1000),
             I(Op::WAIT, 0, 0, 100), I(Op::JC, 10, 0, 10), I(Op::STOP),
             I(Op::CALCV, 0, 0, 1), I(Op::RETI), I(Op::GAP, 3, 0), I(Op::STOP)});
  m.vm.add_inputs({input(500'000, InputEvent::Slip, 0, -101)});
  m.run();
  CHECK_EQ(m.vm.vars[0], 1);
  CHECK(m.vm.errors & tmcl::kErrDeviation);
  CHECK_EQ(m.vm.acc, 0);  // the motor was stopped
  CHECK_EQ(m.vm.axis_param(0, 1), 500);
}

TEST(rst_inside_handler_leaves_it) {
  Machine m({I(Op::VECT, 0, 0, 7), I(Op::SGP, 0, 3, 10), I(Op::EI, 0), I(Op::EI, 255), I(Op::CALCV, 11, 0, 1), I(Op::JC, 2, 0, 9),
             I(Op::WAIT, 0, 0, 100), I(Op::CALCV, 0, 0, 1), I(Op::RST, 0, 0, 4), I(Op::STOP)});
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK(!m.vm.in_handler);
  CHECK_EQ(m.vm.vars[0], 1);
}

TEST(pending_interrupt_served_right_after_reti) {  // E36
  // The handler waits 20 ms; the timer period is 1 ms: after the first interrupt (at 1 ms, when
  // the main loop has counted 24 rounds) the main program never gets a turn again.
  Machine m({I(Op::VECT, 0, 0, 6), I(Op::SGP, 0, 3, 1), I(Op::EI, 0), I(Op::EI, 255), I(Op::CALCV, 0, 1, 1), I(Op::JA, 0, 0, 4),
             I(Op::WAIT, 0, 0, 0), I(Op::CALC, 9, 0, 2), I(Op::WAIT, 0, 0, -1), I(Op::CALCV, 0, 2, 1), I(Op::RETI)},
            test_profile(), 20);
  auto r = m.vm.run({UINT64_MAX, 100'000});
  CHECK(r.halt == Halt::TimeLimit);
  CHECK_EQ(m.vm.vars[1], 24);
  CHECK_EQ(m.vm.vars[2], 4);
}
