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

// Issue 28 item 2: a value outside the profile's range of a parameter is ignored, as on the
// module (E3), but no longer silently: a run-time warning names parameter, value and range,
// under every profile (generic range-checks the parameters its tables list).
TEST(warning_sap_value_out_of_range_on_generic) {
  Machine m({I(Op::SAP, 4, 0, 20000000), I(Op::GAP, 4, 0), I(Op::STOP)}, tmcl::generic_profile(), 20);
  CHECK(m.run().halt == Halt::Stop);
  CHECK_EQ(m.vm.acc, 51200);  // the write was ignored: the default stays
  CHECK_EQ(m.vm.warnings.size(), 1u);
  CHECK(m.vm.warnings[0].kind == RuntimeWarning::ValueOutOfRange);
  CHECK_EQ(m.vm.warnings[0].pc, 0);
  CHECK_EQ(m.vm.warnings[0].message,
           std::string("value 20000000 is outside the range of axis parameter 4 (Maximum positioning speed): 0 to "
                       "16777215 pps"));
  CHECK_EQ(std::string(tmcl::warning_kind_name(RuntimeWarning::ValueOutOfRange)), std::string("value-out-of-range"));
  // A parameter the generic tables do not list takes any value, without a word.
  Machine any({I(Op::SAP, 6, 0, 100000), I(Op::GAP, 6, 0), I(Op::STOP)}, tmcl::generic_profile());
  CHECK(any.run().halt == Halt::Stop);
  CHECK_EQ(any.vm.acc, 100000);
  CHECK(any.vm.warnings.empty());
}

TEST(warning_value_out_of_range_aap_sgp_ror_and_strict) {
  // AAP with the accumulator, SGP of a bank-0 flag, ROR beyond the target speed's range: each
  // one warning, each ignored.
  Machine m({I(Op::CALC, 9, 0, 5000000), I(Op::AAP, 4, 0), I(Op::SGP, 77, 0, 5), I(Op::ROR, 0, 0, 2000000),
             I(Op::ROL, 0, 0, 5), I(Op::STOP)});
  CHECK(m.run().halt == Halt::Stop);
  CHECK_EQ(m.vm.warnings.size(), 3u);
  CHECK_EQ(m.vm.warnings[0].message,
           std::string("value 5000000 is outside the range of axis parameter 4 (max speed): 0 to 1000000"));
  CHECK_EQ(m.vm.warnings[1].message,
           std::string("value 5 is outside the range of global parameter 77 (autostart) of bank 0: 0 to 1"));
  CHECK_EQ(m.vm.warnings[2].message,
           std::string("velocity 2000000 is outside the range of axis parameter 2 (target speed): -1000000 to 1000000"));
  CHECK_EQ(m.vm.warnings[2].pc, 3);
  CHECK_EQ(m.vm.axis_param(0, 4), 1000);
  // --strict: a fault at the SAP, which stays the next instruction.
  Machine s({I(Op::SAP, 140, 0, 9), I(Op::STOP)});
  s.vm.strict = true;
  auto r = s.run();
  CHECK(r.halt == Halt::Fault);
  CHECK_EQ(s.vm.pc, 0);
  CHECK(r.message.find("value 9 is outside the range of axis parameter 140 (microsteps): 0 to 8") != std::string::npos);
}

TEST(direct_mode_out_of_range_is_status_4_without_warning) {
  Machine m({I(Op::STOP)}, tmcl::generic_profile());
  auto reply = m.vm.execute_direct(I(Op::SAP, 4, 0, 20000000));
  CHECK_EQ(static_cast<int>(reply.status), static_cast<int>(tmcl::kStatusInvalidValue));
  CHECK(m.vm.warnings.empty());
  // A 32-bit field read as unsigned is in range: 0xFFFFFFFF for a 0..2^32-1 timer period.
  Machine t({I(Op::STOP)});
  CHECK_EQ(static_cast<int>(t.vm.execute_direct(I(Op::SGP, 0, 3, -1)).status), static_cast<int>(tmcl::kStatusOk));
}

TEST(warning_names_the_range_a_motion_core_refuses_under_generic) {
  // Under generic the linear core keeps to its module's row (TMC2300: speeds up to 32767 pps),
  // stricter than generic's own tables: the warning names the row that refused the value.
  auto core = tmcl::make_motion_core("linear");
  tmcl::Vm vm(tmcl::generic_profile(), *core);
  vm.load({I(Op::SAP, 4, 0, 40000), I(Op::STOP)});
  vm.power_on(nullptr);
  vm.start(0);
  CHECK(vm.run({}).halt == Halt::Stop);
  CHECK_EQ(vm.warnings.size(), 1u);
  if (!vm.warnings.empty())
    CHECK(vm.warnings[0].message.find("value 40000 is outside the range of axis parameter 4") == 0 &&
          vm.warnings[0].message.find(": 0 to 32767") != std::string::npos);
}
