// Run-time warnings (Vm::warnings, Vm::strict): the mistakes the manuals let pass silently (a
// CSUB on a full call stack, RSUB or RETI with nothing to return to, a handler left without
// RETI) are recorded with time, address and kind, each instruction still ignored as the manuals
// say (errata E5, E6, E13); with `strict` each is a runtime fault at that instruction instead.
#include "check.hpp"
#include "machine.hpp"

using namespace vmtest;
using tmcl::Halt;
using tmcl::Op;
using tmcl::RuntimeWarning;

namespace {

std::vector<Instruction> nine_csubs() {
  std::vector<Instruction> p;
  for (int i = 0; i < 9; ++i) p.push_back(I(Op::CSUB, 0, 0, i + 1));  // each calls the next line
  p.push_back(I(Op::STOP));
  return p;
}

// A timer handler at 6 that ends with RSUB (ignored: no call of its own), then STOP.
std::vector<Instruction> handler_without_reti() {
  return {I(Op::VECT, 0, 0, 6), I(Op::SGP, 0, 3, 10), I(Op::EI, 0), I(Op::EI, 255), I(Op::WAIT, 0, 0, 100), I(Op::STOP),
          I(Op::CALCV, 0, 0, 1), I(Op::RSUB), I(Op::STOP)};
}

}  // namespace

TEST(warning_csub_on_full_stack) {  // E5
  Machine m(nine_csubs(), test_profile(), 20);
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.sp, 8);  // still ignored as the manuals say
  CHECK_EQ(m.vm.warnings.size(), 1u);
  CHECK_EQ(m.vm.warnings_total, 1u);
  CHECK(m.vm.warnings[0].kind == RuntimeWarning::CallStackFull);
  CHECK_EQ(m.vm.warnings[0].pc, 8);
  CHECK_EQ(m.vm.warnings[0].at, 8 * 20);  // the ninth CSUB's start
  CHECK_EQ(m.vm.warnings[0].message, std::string("CSUB to 9 with the call stack full (8 return addresses)"));
}

TEST(strict_csub_on_full_stack_faults) {
  Machine m(nine_csubs());
  m.vm.strict = true;
  auto r = m.run();
  CHECK(r.halt == Halt::Fault);
  CHECK_EQ(m.vm.halt_pc, 8);
  CHECK_EQ(m.vm.pc, 8);  // at the CSUB, not past it
  CHECK(r.message.find("the call stack full") != std::string::npos);
  CHECK(r.message.find("(--strict)") != std::string::npos);
  CHECK(m.vm.warnings.empty());
}

TEST(warning_rsub_on_empty_stack) {  // E6
  Machine m({I(Op::RSUB), I(Op::CALC, 9, 0, 3), I(Op::STOP)});
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.acc, 3);
  CHECK_EQ(m.vm.warnings.size(), 1u);
  CHECK(m.vm.warnings[0].kind == RuntimeWarning::ReturnWithoutCall);
  CHECK_EQ(m.vm.warnings[0].pc, 0);
  m.vm.power_on(nullptr);  // power-up forgets them
  CHECK(m.vm.warnings.empty());
  CHECK_EQ(m.vm.warnings_total, 0u);
}

TEST(warning_reti_outside_handler_and_strict) {  // E13
  Machine m({I(Op::CALC, 9, 0, 1), I(Op::RETI), I(Op::STOP)});
  CHECK(m.run().halt == Halt::Stop);
  CHECK_EQ(m.vm.warnings.size(), 1u);
  CHECK(m.vm.warnings[0].kind == RuntimeWarning::RetiOutsideHandler);
  CHECK_EQ(m.vm.warnings[0].pc, 1);
  Machine s({I(Op::CALC, 9, 0, 1), I(Op::RETI), I(Op::STOP)});
  s.vm.strict = true;
  auto r = s.run();
  CHECK(r.halt == Halt::Fault);
  CHECK_EQ(s.vm.halt_pc, 1);
}

TEST(warning_handler_left_by_rsub_and_stop) {
  Machine m(handler_without_reti());
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.halt_pc, 8);
  CHECK_EQ(m.vm.vars[0], 1);
  CHECK_EQ(m.vm.warnings.size(), 2u);
  CHECK(m.vm.warnings[0].kind == RuntimeWarning::ReturnWithoutCall);
  CHECK_EQ(m.vm.warnings[0].pc, 7);
  CHECK(m.vm.warnings[1].kind == RuntimeWarning::HandlerWithoutReti);
  CHECK_EQ(m.vm.warnings[1].pc, 8);
  CHECK_EQ(m.vm.warnings[1].message, std::string("STOP inside the handler of interrupt 0: the handler is left without RETI"));
  Machine s(handler_without_reti());
  s.vm.strict = true;
  auto rs = s.run();
  CHECK(rs.halt == Halt::Fault);
  CHECK_EQ(s.vm.halt_pc, 7);  // at the RSUB
}

TEST(correct_calls_and_handlers_have_no_warnings) {
  // main calls the subroutine at 9 once; the timer handler at 7 calls it too and ends with RETI
  Machine m({I(Op::VECT, 0, 0, 7), I(Op::SGP, 0, 3, 10), I(Op::EI, 0), I(Op::EI, 255), I(Op::CSUB, 0, 0, 9),
             I(Op::WAIT, 0, 0, 5), I(Op::STOP),
             I(Op::CSUB, 0, 0, 9), I(Op::RETI),
             I(Op::CALCV, 0, 0, 1), I(Op::RSUB)});
  m.vm.strict = true;
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK(m.vm.warnings.empty());
  CHECK_EQ(m.vm.vars[0], 6);  // main once, the handler at 10, 20, 30, 40 and 50 ms
}

TEST(warnings_are_capped_with_a_count) {
  std::vector<Instruction> p;
  for (int i = 0; i < 150; ++i) p.push_back(I(Op::RSUB));
  p.push_back(I(Op::STOP));
  Machine m(p);
  m.run();
  CHECK_EQ(m.vm.warnings.size(), tmcl::Vm::kMaxWarnings);
  CHECK_EQ(m.vm.warnings_total, 150u);
  CHECK_EQ(m.vm.last_warning.pc, 149);
}
