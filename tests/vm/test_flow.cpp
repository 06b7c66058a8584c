// Control flow: JA, JC (every condition), CSUB/RSUB and the 8-entry stack, CALL, DJNZ, RST,
// STOP, and the faults: jump outside the program, unknown opcode, running off the end,
// a command the module does not have (docs/errata.md E4-E6, E11, E19-E21).
#include <limits>

#include "check.hpp"
#include "machine.hpp"

using namespace vmtest;
using tmcl::Halt;
using tmcl::Op;

TEST(ja_and_stop) {
  Machine m({I(Op::JA, 0, 0, 2), I(Op::CALC, 9, 0, 1), I(Op::STOP)});
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.acc, 0);
  CHECK_EQ(m.vm.pc, 2);
  CHECK_EQ(m.vm.steps, 2u);
}

TEST(jc_every_condition) {
  // acc compared with 5; each JC jumps over a "CALC LOAD 1" marker when its condition holds.
  struct Case {
    std::int32_t acc;
    int cond;
    bool jumps;
  } cases[] = {
      {5, 0, true},  {4, 0, false}, {4, 1, true},  {5, 1, false}, {5, 2, true},  {6, 2, false},
      {6, 3, true},  {5, 3, false}, {6, 4, true},  {5, 4, false}, {5, 5, true},  {6, 5, true},
      {4, 5, false}, {4, 6, true},  {5, 6, false}, {5, 7, true},  {4, 7, true},  {6, 7, false},
      {5, 8, false}, {5, 9, false}, {5, 10, false}, {5, 11, false}, {5, 12, false},
  };
  for (const auto& c : cases) {
    Machine m({I(Op::CALC, 9, 0, c.acc), I(Op::COMP, 0, 0, 5), I(Op::JC, c.cond, 0, 4), I(Op::CALCX, 9), I(Op::STOP)});
    m.run();
    CHECK_EQ(m.vm.x == 0, c.jumps);
  }
}

TEST(jc_error_flags) {
  Machine m({I(Op::WAIT, 1, 0, 1), I(Op::ROR, 0, 0, 0), I(Op::JC, 8, 0, 4), I(Op::STOP), I(Op::CALC, 9, 0, 77), I(Op::STOP)});
  // WAIT POS with a 1-tick timeout while the motor is at its target: no timeout
  m.run();
  CHECK_EQ(m.vm.acc, 0);
}

TEST(csub_rsub_nesting_and_limit) {  // E5
  // sub: CALCV ADD,0,1 ; CSUB sub (recursion) -> 8 frames, then the 9th CSUB is ignored
  std::vector<Instruction> p = {
      I(Op::CSUB, 0, 0, 2), I(Op::STOP),
      I(Op::CALCV, 0, 0, 1), I(Op::CALCV, 11, 0, 20), I(Op::JC, 4, 0, 6), I(Op::CSUB, 0, 0, 2),
      I(Op::RSUB)};
  Machine m(p);
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.sp, 0);
  // main's CSUB plus 7 recursive ones fill the stack; the 9th CSUB is ignored and falls through
  // to RSUB, which unwinds all 8 levels back to STOP
  CHECK_EQ(m.vm.vars[0], 8);
}

TEST(csub_ninth_is_ignored) {
  std::vector<Instruction> p;
  for (int i = 0; i < 9; ++i) p.push_back(I(Op::CSUB, 0, 0, i + 1));  // each calls the next line
  p.push_back(I(Op::STOP));
  Machine m(p);
  m.run();
  CHECK_EQ(m.vm.sp, 8);
  CHECK_EQ(m.vm.pc, 9);
}

TEST(rsub_on_empty_stack_is_ignored) {
  Machine m({I(Op::RSUB), I(Op::CALC, 9, 0, 3), I(Op::STOP)});
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.acc, 3);
}

TEST(call_conditional) {
  Machine m({I(Op::COMP, 0, 0, 1), I(Op::CALL, 6, 0, 5), I(Op::CALL, 4, 0, 6), I(Op::STOP), I(Op::STOP),
             I(Op::CALC, 9, 0, 11), I(Op::RSUB)});
  m.run();
  CHECK_EQ(m.vm.acc, 11);  // LT held (0 < 1): called; GT after CALC LOAD 11 held too: called again? no: STOP
}

TEST(djnz_counts_down) {  // E4
  Machine m({I(Op::SGP, 42, 2, 100), I(Op::CALCV, 0, 1, 1), I(Op::DJNZ, 42, 0, 1), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.vars[1], 100);
  CHECK_EQ(m.vm.vars[42], 0);
}

TEST(djnz_keeps_flags_and_wraps) {
  Machine m({I(Op::COMP, 0, 0, 1), I(Op::DJNZ, 3, 0, 3), I(Op::STOP), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.vars[3], -1);  // 0 - 1: not zero, jumps
  CHECK_EQ(m.vm.pc, 3);
  CHECK_EQ(m.vm.flags, tmcl::kFlagLower);
}

TEST(rst_clears_registers_stack_flags) {
  Machine m({I(Op::CALCV, 0, 9, 1), I(Op::CALCV, 11, 9, 3), I(Op::JC, 2, 0, 7), I(Op::CALC, 9, 0, 5), I(Op::CALCX, 9),
             I(Op::CSUB, 0, 0, 6), I(Op::RST, 0, 0, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.vars[9], 3);
  CHECK_EQ(m.vm.acc, 0);
  CHECK_EQ(m.vm.x, 0);
  CHECK_EQ(m.vm.sp, 0);
  CHECK_EQ(m.vm.flags, tmcl::kFlagZero | tmcl::kFlagEqual);  // from the final CALCV COMP
}

TEST(jump_outside_program_faults) {  // E19
  Machine m({I(Op::JA, 0, 0, 99), I(Op::STOP)});
  auto r = m.run();
  CHECK(r.halt == Halt::Fault);
  CHECK(r.message.find("outside the program") != std::string::npos);
  CHECK_EQ(m.vm.halt_pc, 0);
  Machine n({I(Op::CSUB, 0, 0, -1), I(Op::STOP)});
  CHECK(n.run().halt == Halt::Fault);
  Machine v({I(Op::VECT, 0, 0, 50), I(Op::STOP)});
  CHECK(v.run().halt == Halt::Fault);
}

TEST(unknown_opcode_faults) {  // E20
  Machine m({Instruction{99, 0, 0, 0}, I(Op::STOP)});
  auto r = m.run();
  CHECK(r.halt == Halt::Fault);
  CHECK(r.message.find("unknown opcode 99") != std::string::npos);
  Machine c({Instruction{129, 0, 0, 0}});
  CHECK(c.run().message.find("control command") != std::string::npos);
}

TEST(running_past_the_end_faults) {  // E21
  Machine m({I(Op::CALC, 9, 0, 1)});
  auto r = m.run();
  CHECK(r.halt == Halt::Fault);
  CHECK(r.message.find("past the end") != std::string::npos);
}

TEST(unavailable_command_faults) {
  Machine m({I(Op::UF0), I(Op::STOP)});  // the test profile lacks UF0
  auto r = m.run();
  CHECK(r.halt == Halt::Fault);
  CHECK(r.message.find("not available on test") != std::string::npos);
}

TEST(user_function_faults) {  // E15
  Machine m({I(Op::UF1), I(Op::STOP)});
  CHECK(m.run().halt == Halt::Fault);
}

TEST(step_limit) {
  Machine m({I(Op::JA, 0, 0, 0)});
  auto r = m.run({1000, tmcl::kNever});
  CHECK(r.halt == Halt::StepLimit);
  CHECK_EQ(m.vm.steps, 1000u);
}

TEST(time_limit_in_a_loop) {
  Machine m({I(Op::JA, 0, 0, 0)}, test_profile(), 20);
  auto r = m.vm.run({UINT64_MAX, 1000});
  CHECK(r.halt == Halt::TimeLimit);
  CHECK_EQ(m.vm.now, 1000);
  CHECK_EQ(m.vm.steps, 50u);
}

TEST(push_pop_stack) {  // E12
  Machine m({I(Op::CALC, 9, 0, 7), I(Op::PUSHA), I(Op::CALC, 9, 0, 1), I(Op::POPX), I(Op::POPA), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.x, 7);
  CHECK_EQ(m.vm.acc, 1);  // pop on an empty stack is ignored
}

namespace {
// Runs a program twice, once on the fast path and once traced (the table dispatch for every
// instruction), and checks that both end in the same state at the same instant.
void check_paths_agree(const std::vector<Instruction>& prog, tmcl::Limits lim, tmcl::SimTime instr, std::uint8_t errors = 0) {
  Machine fast(prog, test_profile(), instr), traced(prog, test_profile(), instr);
  NullTrace t;
  traced.vm.trace = &t;
  fast.vm.errors = traced.vm.errors = errors;
  auto a = fast.vm.run(lim);
  auto b = traced.vm.run(lim);
  CHECK(a.halt == b.halt);
  CHECK_EQ(a.message, b.message);
  CHECK_EQ(fast.vm.now, traced.vm.now);
  CHECK_EQ(fast.vm.steps, traced.vm.steps);
  CHECK_EQ(fast.vm.pc, traced.vm.pc);
  CHECK_EQ(fast.vm.acc, traced.vm.acc);
  CHECK_EQ(fast.vm.x, traced.vm.x);
  CHECK_EQ(fast.vm.flags, traced.vm.flags);
  CHECK(fast.vm.vars == traced.vm.vars);
}
}  // namespace

TEST(fast_path_and_fused_forms_are_unobservable) {
  // CALC/DJNZ and CALCV/DJNZ pairs (fused), a 10 ms timer whose handler samples the counters so
  // that an interrupt between the two halves of a pair would show, odd step limits.
  std::vector<Instruction> p = {
      I(Op::SGP, 0, 2, 5000), I(Op::VECT, 0, 0, 11), I(Op::SGP, 0, 3, 10), I(Op::EI, 0), I(Op::EI, 255),
      I(Op::CALC, 0, 0, 3), I(Op::DJNZ, 0, 0, 5), I(Op::SGP, 0, 2, 777), I(Op::CALCV, 1, 2, 7), I(Op::DJNZ, 0, 0, 8),
      I(Op::STOP),
      I(Op::CALCX, 9), I(Op::CALCVX, 0, 3), I(Op::GGP, 0, 2), I(Op::CALCVA, 0, 4), I(Op::COMP, 0, 0, 100), I(Op::JC, 4, 0, 18),
      I(Op::CALCV, 0, 5, 1), I(Op::RETI)};
  for (tmcl::SimTime instr : {0, 7, 20, 333})
    for (std::uint64_t steps : {std::uint64_t{1}, std::uint64_t{6}, std::uint64_t{7}, std::uint64_t{1001}, std::uint64_t{12345}, UINT64_MAX})
      check_paths_agree(p, {steps, tmcl::kNever}, instr);
  check_paths_agree(p, {UINT64_MAX, 123'457}, 20);
}

// Every CALC and CALCV operation, plain (followed by STOP) and fused with a DJNZ, on the edge values
// of E1 (division and modulo by zero and by -1, overflow), gives the table dispatch's result: the
// fast path instantiates the ALU per operation (ops::arith_of), the table dispatch picks it at run
// time (issue 42).
TEST(every_calc_operation_agrees_on_fast_fused_and_traced_paths) {
  const std::int32_t kMin = std::numeric_limits<std::int32_t>::min(), kMax = std::numeric_limits<std::int32_t>::max();
  for (int t = 0; t <= 9; ++t)
    for (std::int32_t a : {kMin, -7, 0, 7, kMax})
      for (std::int32_t v : {kMin, -1, 0, 3, kMax}) {
        // acc = a, v[1] = a; CALC t, v / DJNZ (fused, two rounds), CALCV t, v / DJNZ, CALC t, v / CALCV t, v alone.
        std::vector<Instruction> p = {I(Op::CALC, 9, 0, a),  I(Op::SGP, 1, 2, a),   I(Op::SGP, 0, 2, 2),
                                      I(Op::CALC, t, 0, v),  I(Op::DJNZ, 0, 0, 3),  I(Op::SGP, 0, 2, 2),
                                      I(Op::CALCV, t, 1, v), I(Op::DJNZ, 0, 0, 6),  I(Op::CALC, t, 0, v),
                                      I(Op::CALCV, t, 1, v), I(Op::STOP)};
        check_paths_agree(p, {UINT64_MAX, tmcl::kNever}, 20);
      }
}

// JA, JC and DJNZ run pre-decoded on the fast path (the target checked once, JC's condition as a
// mask): every condition (the unknown ones too) on every flag and error flag, and targets outside
// the program (a fault where the table dispatch faults), agree with the table dispatch (issue 42).
TEST(pre_decoded_jumps_agree_with_the_table_dispatch) {
  for (int cond : {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 15, 16, 200})
    for (int errors : {0, 1, 2, 4, 8, 15})
      for (std::int32_t acc : {4, 5, 6})
        for (std::int32_t target : {5, 99, -1}) {
          check_paths_agree({I(Op::CALC, 9, 0, acc), I(Op::COMP, 0, 0, 5), I(Op::JC, cond, 0, target), I(Op::CALCX, 9),
                             I(Op::STOP), I(Op::STOP)},
                            {UINT64_MAX, tmcl::kNever}, 20, static_cast<std::uint8_t>(errors));
          check_paths_agree({I(Op::SGP, 0, 2, acc - 4), I(Op::DJNZ, 0, 0, target), I(Op::JA, 0, 0, target), I(Op::STOP),
                             I(Op::STOP), I(Op::STOP)},
                            {UINT64_MAX, tmcl::kNever}, 20, static_cast<std::uint8_t>(errors));
        }
  Machine m({I(Op::CALC, 9, 0, 5), I(Op::COMP, 0, 0, 5), I(Op::JC, 0, 0, 99), I(Op::STOP)});
  auto r = m.run();  // JC ZE holds: the jump outside faults at its address, as JA's (E19)
  CHECK(r.halt == Halt::Fault);
  CHECK(r.message.find("outside the program") != std::string::npos);
  CHECK_EQ(m.vm.halt_pc, 2);
  Machine d({I(Op::SGP, 0, 2, 2), I(Op::DJNZ, 0, 0, 99), I(Op::STOP)});
  CHECK(d.run().halt == Halt::Fault);
  CHECK_EQ(d.vm.halt_pc, 1);
}

// The life cycle belongs to the VM (control commands 128, 130, 131 and a debugger use these):
// step runs exactly one instruction and leaves the program in Step; a WAIT is entered, not
// jumped over; stop_application stops a stepping program; reset_application clears registers
// and goes to address 0 in Reset; start clears a fault.
TEST(life_cycle_step_stop_reset) {
  Machine m({I(Op::CALC, 9, 0, 5), I(Op::CALC, 0, 0, 2), I(Op::WAIT, 0, 0, 10), I(Op::CSUB, 0, 0, 5), I(Op::STOP),
             I(Op::RSUB)},
            test_profile(), 20);
  m.vm.reset_application();
  CHECK(m.vm.status == tmcl::AppStatus::Reset);
  CHECK(m.vm.step().halt == Halt::StepLimit);
  CHECK_EQ(m.vm.pc, 1);
  CHECK_EQ(m.vm.acc, 5);
  CHECK_EQ(m.vm.steps, 1u);
  CHECK_EQ(m.vm.now, 20);
  CHECK(m.vm.status == tmcl::AppStatus::Step);
  m.vm.step();
  CHECK_EQ(m.vm.acc, 7);
  m.vm.step();  // WAIT TICKS 10: entered, time does not jump to its end
  CHECK_EQ(m.vm.pc, 2);
  CHECK(m.vm.wait.active);
  CHECK_EQ(m.vm.now, 60);
  CHECK(m.vm.status == tmcl::AppStatus::Step);
  m.vm.stop_application();
  CHECK(m.vm.status == tmcl::AppStatus::Stopped);
  m.vm.stop_application();  // stopping a stopped program changes nothing
  CHECK(m.vm.status == tmcl::AppStatus::Stopped);
  m.vm.reset_application();
  CHECK_EQ(m.vm.pc, 0);
  CHECK_EQ(m.vm.acc, 0);
  CHECK(!m.vm.wait.active);
  CHECK(m.vm.status == tmcl::AppStatus::Reset);
  CHECK_EQ(m.vm.halt_pc, -1);
  m.vm.start(3);
  CHECK(m.vm.step().halt == Halt::StepLimit);  // CSUB: one stack entry
  CHECK_EQ(m.vm.pc, 5);
  CHECK_EQ(m.vm.sp, 1);
  m.vm.reset_application();
  CHECK_EQ(m.vm.sp, 0);
  CHECK_EQ(m.vm.pc, 0);

  Machine f({I(Op::JA, 0, 0, 99), I(Op::STOP)});
  auto r = f.vm.step();
  CHECK(r.halt == Halt::Fault);
  CHECK(f.vm.faulted());
  CHECK(f.vm.fault_message().find("outside the program") != std::string::npos);
  CHECK(f.vm.status == tmcl::AppStatus::Stopped);
  f.vm.start(1);
  CHECK(!f.vm.faulted());
  CHECK(f.vm.fault_message().empty());
  CHECK(f.run().halt == Halt::Stop);
}
