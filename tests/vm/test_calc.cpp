// CALC, CALCX, COMP and the CALCVV/VA/AV/VX/XV/V family: every operation, the flags they set,
// and the errata decisions on division by zero and 32-bit overflow (docs/errata.md E1, E2).
#include <climits>

#include "check.hpp"
#include "machine.hpp"

using namespace vmtest;
using tmcl::Op;

namespace {
// Runs `prog` (a STOP is appended) from acc = a, x = xv and returns the machine.
Machine calc_run(std::vector<Instruction> prog, std::int32_t a = 0, std::int32_t xv = 0) {
  prog.push_back(I(Op::STOP));
  Machine m(prog);
  m.vm.acc = a;
  m.vm.x = xv;
  m.run();
  return m;
}
std::int32_t calc_acc(int op, std::int32_t a, std::int32_t v) { return calc_run({I(Op::CALC, op, 0, v)}, a).vm.acc; }
}  // namespace

TEST(calc_every_operation) {
  CHECK_EQ(calc_acc(0, 5, 3), 8);
  CHECK_EQ(calc_acc(1, 5, 3), 2);
  CHECK_EQ(calc_acc(2, 5, -3), -15);
  CHECK_EQ(calc_acc(3, 7, 2), 3);
  CHECK_EQ(calc_acc(3, -7, 2), -3);   // truncation toward zero
  CHECK_EQ(calc_acc(4, 7, 3), 1);
  CHECK_EQ(calc_acc(4, -7, 3), -1);   // sign of the dividend
  CHECK_EQ(calc_acc(5, 0b1100, 0b1010), 0b1000);
  CHECK_EQ(calc_acc(6, 0b1100, 0b1010), 0b1110);
  CHECK_EQ(calc_acc(7, 0b1100, 0b1010), 0b0110);
  CHECK_EQ(calc_acc(8, 5, 12345), ~5);  // NOT inverts the accumulator, value ignored
  CHECK_EQ(calc_acc(9, 5, 42), 42);
}

TEST(calc_division_by_zero_leaves_target) {  // E1
  CHECK_EQ(calc_acc(3, 77, 0), 77);
  CHECK_EQ(calc_acc(4, 77, 0), 77);
  auto m = calc_run({I(Op::CALC, 3, 0, 0)}, 77);
  CHECK_EQ(m.vm.flags, tmcl::kFlagGreater);  // flags from the (unchanged) result
  CHECK(!m.vm.faulted());
}

TEST(calc_overflow_wraps) {  // E1
  CHECK_EQ(calc_acc(0, INT_MAX, 1), INT_MIN);
  CHECK_EQ(calc_acc(1, INT_MIN, 1), INT_MAX);
  CHECK_EQ(calc_acc(2, 65536, 65536), 0);
  CHECK_EQ(calc_acc(2, INT_MAX, 2), -2);
  CHECK_EQ(calc_acc(3, INT_MIN, -1), INT_MIN);
  CHECK_EQ(calc_acc(4, INT_MIN, -1), 0);
}

TEST(calc_invalid_type_ignored) {
  auto m = calc_run({I(Op::CALC, 10, 0, 3)}, 9);  // SWAP is not a CALC operation
  CHECK_EQ(m.vm.acc, 9);
  CHECK_EQ(m.vm.pc, 1);
}

TEST(calc_sets_flags_from_result) {  // E2
  CHECK_EQ(calc_run({I(Op::CALC, 1, 0, 5)}, 5).vm.flags, tmcl::kFlagZero | tmcl::kFlagEqual);
  CHECK_EQ(calc_run({I(Op::CALC, 1, 0, 6)}, 5).vm.flags, tmcl::kFlagLower);
  CHECK_EQ(calc_run({I(Op::CALC, 0, 0, 1)}, 5).vm.flags, tmcl::kFlagGreater);
}

TEST(comp_sets_comparison_flags) {
  CHECK_EQ(calc_run({I(Op::COMP, 0, 0, 1000)}, 1000).vm.flags, tmcl::kFlagZero | tmcl::kFlagEqual);
  CHECK_EQ(calc_run({I(Op::COMP, 0, 0, 1000)}, 1001).vm.flags, tmcl::kFlagGreater);
  CHECK_EQ(calc_run({I(Op::COMP, 0, 0, 1000)}, -5).vm.flags, tmcl::kFlagLower);
  // COMP compares, it does not subtract: no overflow in the comparison
  CHECK_EQ(calc_run({I(Op::COMP, 0, 0, INT_MIN)}, INT_MAX).vm.flags, tmcl::kFlagGreater);
  auto m = calc_run({I(Op::COMP, 0, 0, 3)}, 7);
  CHECK_EQ(m.vm.acc, 7);
}

TEST(calcx_operations) {
  CHECK_EQ(calc_run({I(Op::CALCX, 0)}, 5, 3).vm.acc, 8);
  CHECK_EQ(calc_run({I(Op::CALCX, 1)}, 5, 3).vm.acc, 2);
  CHECK_EQ(calc_run({I(Op::CALCX, 2)}, 5, 3).vm.acc, 15);
  CHECK_EQ(calc_run({I(Op::CALCX, 3)}, 15, 0).vm.acc, 15);  // E1
  CHECK_EQ(calc_run({I(Op::CALCX, 4)}, 15, 4).vm.acc, 3);
  CHECK_EQ(calc_run({I(Op::CALCX, 8)}, 5, 3).vm.acc, ~3);   // E24: acc = NOT X
  auto load = calc_run({I(Op::CALCX, 9)}, 5, 3);             // LOAD copies acc to X
  CHECK_EQ(load.vm.x, 5);
  CHECK_EQ(load.vm.acc, 5);
  auto swap = calc_run({I(Op::CALCX, 10)}, 5, 3);
  CHECK_EQ(swap.vm.acc, 3);
  CHECK_EQ(swap.vm.x, 5);
  auto comp = calc_run({I(Op::CALCX, 11)}, 5, 3);  // COMP is not a CALCX operation: ignored
  CHECK_EQ(comp.vm.acc, 5);
}

TEST(calc_variable_family) {
  // CALCVV: var1 op= var2
  {
    auto m = calc_run({I(Op::SGP, 65, 2, 100), I(Op::SGP, 42, 2, 30), I(Op::CALCVV, 1, 65, 42)});
    CHECK_EQ(m.vm.vars[65], 70);
    CHECK_EQ(m.vm.vars[42], 30);
  }
  {
    auto m = calc_run({I(Op::SGP, 1, 2, 100), I(Op::SGP, 2, 2, 30), I(Op::CALCVV, 3, 1, 2)});
    CHECK_EQ(m.vm.vars[1], 3);  // var1 / var2
  }
  {
    auto m = calc_run({I(Op::SGP, 1, 2, 7), I(Op::SGP, 2, 2, 9), I(Op::CALCVV, 10, 1, 2)});
    CHECK_EQ(m.vm.vars[1], 9);
    CHECK_EQ(m.vm.vars[2], 7);
  }
  {
    auto m = calc_run({I(Op::SGP, 1, 2, 7), I(Op::SGP, 2, 2, 9), I(Op::CALCVV, 11, 1, 2)});
    CHECK_EQ(m.vm.flags, tmcl::kFlagLower);
    CHECK_EQ(m.vm.vars[1], 7);
  }
  {
    auto m = calc_run({I(Op::SGP, 1, 2, 7), I(Op::CALCVV, 8, 2, 1)});
    CHECK_EQ(m.vm.vars[2], ~7);  // NOT copies the inverted var2
  }
  {
    auto m = calc_run({I(Op::CALCVV, 0, 1, 300)});  // var2 outside 0..255: ignored
    CHECK(!m.vm.faulted());
    CHECK_EQ(m.vm.pc, 1);
  }
  // CALCVA / CALCAV / CALCVX / CALCXV
  {
    auto m = calc_run({I(Op::SGP, 27, 2, 100), I(Op::CALCVA, 1, 27)}, 40);
    CHECK_EQ(m.vm.vars[27], 60);
    CHECK_EQ(m.vm.acc, 40);
  }
  {
    auto m = calc_run({I(Op::SGP, 27, 2, 100), I(Op::CALCAV, 1, 27)}, 40);
    CHECK_EQ(m.vm.acc, -60);
  }
  {
    auto m = calc_run({I(Op::SGP, 27, 2, 100), I(Op::CALCAV, 10, 27)}, 40);
    CHECK_EQ(m.vm.acc, 100);
    CHECK_EQ(m.vm.vars[27], 40);
  }
  {
    auto m = calc_run({I(Op::SGP, 27, 2, 100), I(Op::CALCVX, 2, 27)}, 0, 3);
    CHECK_EQ(m.vm.vars[27], 300);
  }
  {
    auto m = calc_run({I(Op::SGP, 27, 2, 100), I(Op::CALCXV, 9, 27)}, 0, 3);
    CHECK_EQ(m.vm.x, 100);
  }
  {
    auto m = calc_run({I(Op::SGP, 27, 2, 100), I(Op::CALCXV, 11, 27)}, 0, 300);
    CHECK_EQ(m.vm.flags, tmcl::kFlagGreater);
  }
  // CALCV: var op= value; NOT inverts the variable; SWAP is not accepted
  {
    auto m = calc_run({I(Op::SGP, 27, 2, 10000), I(Op::CALCV, 1, 27, 5000)});
    CHECK_EQ(m.vm.vars[27], 5000);
  }
  {
    auto m = calc_run({I(Op::SGP, 27, 2, 5), I(Op::CALCV, 8, 27, 99)});
    CHECK_EQ(m.vm.vars[27], ~5);
  }
  {
    auto m = calc_run({I(Op::SGP, 27, 2, 5), I(Op::CALCV, 11, 27, 5)});
    CHECK_EQ(m.vm.flags, tmcl::kFlagZero | tmcl::kFlagEqual);
  }
  {
    auto m = calc_run({I(Op::SGP, 27, 2, 5), I(Op::CALCV, 10, 27, 9)});
    CHECK_EQ(m.vm.vars[27], 5);
  }
  {
    auto m = calc_run({I(Op::SGP, 27, 2, INT_MAX), I(Op::CALCV, 0, 27, 1)});
    CHECK_EQ(m.vm.vars[27], INT_MIN);
  }
}
