// Coverage counting in the run loop (Vm::count_coverage, for tmclrun --test --coverage): every
// instruction's executions and every JC, CALL and DJNZ whose condition held, the same on the fast
// path (fused CALC+DJNZ included), traced, in slices of a time limit, inside interrupt handlers
// and around a debugger trap; and nothing counted unless asked.
#include "check.hpp"
#include "machine.hpp"

using namespace vmtest;
using tmcl::Halt;
using tmcl::Op;

namespace {

// v0 = 3; loop: acc += 1, DJNZ v0 (fused on the fast path); COMP 3; JC NE (not taken); CALL EQ
// (taken); STOP; the subroutine's RSUB.
std::vector<Instruction> loop_program() {
  return {I(Op::SGP, 0, 2, 3), I(Op::CALC, 0, 0, 1), I(Op::DJNZ, 0, 0, 1), I(Op::COMP, 0, 0, 3),
          I(Op::JC, 3, 0, 6),  I(Op::CALL, 2, 0, 7), I(Op::STOP),          I(Op::RSUB)};
}
const std::vector<std::uint64_t> kLoopExecuted = {1, 3, 3, 1, 1, 1, 1, 1, 0};  // the sentinel last
const std::vector<std::uint64_t> kLoopTaken = {0, 0, 2, 0, 0, 1, 0, 0, 0};

}  // namespace

TEST(coverage_is_not_counted_unless_asked) {
  Machine m(loop_program());
  CHECK(m.run().halt == Halt::Stop);
  CHECK(m.vm.executed.empty());
  CHECK(m.vm.taken.empty());
}

TEST(coverage_counts_instructions_and_branches_on_the_fast_path) {
  Machine m(loop_program(), test_profile(), 20);
  m.vm.count_coverage();
  CHECK(m.run().halt == Halt::Stop);
  CHECK(m.vm.executed == kLoopExecuted);
  CHECK(m.vm.taken == kLoopTaken);
  CHECK_EQ(m.vm.acc, 3);
}

TEST(coverage_counts_the_same_traced) {
  Machine m(loop_program(), test_profile(), 20);
  NullTrace t;
  m.vm.trace = &t;
  m.vm.count_coverage();
  CHECK(m.run().halt == Halt::Stop);
  CHECK(m.vm.executed == kLoopExecuted);
  CHECK(m.vm.taken == kLoopTaken);
}

TEST(coverage_counts_the_same_in_slices_of_time) {
  // A run cut at every instant an instruction could end (the test runner stops at each
  // expectation's instant) counts what one run counts, fused pairs split at a limit included.
  Machine m(loop_program(), test_profile(), 20);
  m.vm.count_coverage();
  tmcl::RunResult r{Halt::TimeLimit, ""};
  for (tmcl::SimTime until = 10; r.halt == Halt::TimeLimit; until += 10) r = m.vm.run({UINT64_MAX, until});
  CHECK(r.halt == Halt::Stop);
  CHECK(m.vm.executed == kLoopExecuted);
  CHECK(m.vm.taken == kLoopTaken);
}

TEST(coverage_counts_a_djnz_that_stops_looping_and_a_jc_both_ways) {
  // JC GT back to the loop while acc > 0: taken 4 times, not taken once.
  Machine m({I(Op::CALC, 9, 0, 5), I(Op::CALC, 1, 0, 1), I(Op::COMP, 0, 0, 0), I(Op::JC, 4, 0, 1), I(Op::STOP)}, test_profile(), 20);
  m.vm.count_coverage();
  CHECK(m.run().halt == Halt::Stop);
  CHECK_EQ(m.vm.executed[3], 5u);
  CHECK_EQ(m.vm.taken[3], 4u);
  CHECK_EQ(m.vm.executed[4], 1u);
}

TEST(coverage_counts_interrupt_handlers) {
  // Timer 0 every 100 ms while the main program waits 550 ms: the handler runs five times.
  Machine m({I(Op::VECT, 0, 0, 6), I(Op::SGP, 0, 3, 100), I(Op::EI, 0), I(Op::EI, 255), I(Op::WAIT, 0, 0, 55), I(Op::STOP),
             I(Op::CALCV, 0, 1, 1), I(Op::RETI)},
            test_profile(), 20);
  m.vm.count_coverage();
  CHECK(m.run().halt == Halt::Stop);
  CHECK_EQ(m.vm.vars[1], 5);
  CHECK_EQ(m.vm.executed[6], 5u);
  CHECK_EQ(m.vm.executed[7], 5u);
  CHECK_EQ(m.vm.executed[4], 1u);  // a WAIT is one instruction, however long it waits
  CHECK_EQ(m.vm.executed[5], 1u);
}

TEST(coverage_does_not_count_a_trapped_instruction_until_it_runs) {
  Machine m(loop_program(), test_profile(), 20);
  m.vm.count_coverage();
  m.vm.set_trap(3, true);
  CHECK(m.run().halt == Halt::Break);
  CHECK_EQ(m.vm.executed[3], 0u);
  CHECK_EQ(m.vm.executed[2], 3u);
  m.vm.set_trap(3, false);
  CHECK(m.run().halt == Halt::Stop);
  CHECK(m.vm.executed == kLoopExecuted);
  CHECK(m.vm.taken == kLoopTaken);
}

TEST(coverage_does_not_count_a_jump_that_faults) {
  Machine m({I(Op::COMP, 0, 0, 0), I(Op::JC, 0, 0, 99)}, test_profile(), 20);
  m.vm.count_coverage();
  CHECK(m.run().halt == Halt::Fault);
  CHECK_EQ(m.vm.executed[1], 1u);
  CHECK_EQ(m.vm.taken[1], 0u);
}

TEST(coverage_follows_a_new_program) {
  // A program loaded while counting (a host's download) is counted afresh, sized to it.
  Machine m({I(Op::STOP)}, test_profile(), 20);
  m.vm.count_coverage();
  m.vm.load(loop_program());
  m.vm.start(0);
  CHECK(m.run().halt == Halt::Stop);
  CHECK(m.vm.executed == kLoopExecuted);
  CHECK(m.vm.taken == kLoopTaken);
}
