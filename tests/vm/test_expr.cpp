// Expressions (tmcl/expr.hpp), the debugger's and the test runner's: `position M` and `velocity M`
// as words for axis parameters 1 and 3, names that still resolve to labels, and errors that say
// where they are and which name was meant.
#include "check.hpp"
#include "machine.hpp"
#include "tmcl/expr.hpp"

using namespace vmtest;
using tmcl::Op;

namespace {

std::int64_t value_of(const std::string& text, tmcl::Vm& vm, const tmcl::ProgramInfo& info = {}) {
  tmcl::Expr e;
  std::string err;
  CHECK(tmcl::parse_expr(text, info, e, err));
  CHECK_EQ(err, "");
  std::int64_t v = -12345;
  CHECK(tmcl::eval_expr(e, vm, v, err));
  CHECK_EQ(err, "");
  return v;
}

}  // namespace

TEST(expr_position_and_velocity_are_axis_parameters_1_and_3) {
  // A rotation at 1000 pps for 0.5 s: the motor is at 500 and still turning.
  Machine m({I(Op::ROR, 0, 0, 1000), I(Op::WAIT, 0, 0, 50), I(Op::STOP)}, test_profile(), 20);
  m.run({1'000'000, 400'000});
  CHECK_EQ(value_of("position 0", m.vm), value_of("ap(1, 0)", m.vm));
  CHECK_EQ(value_of("velocity 0", m.vm), 1000);
  CHECK_EQ(value_of("velocity(0)", m.vm), 1000);
  CHECK_EQ(value_of("position 0 + 1", m.vm), value_of("ap(1, 0)", m.vm) + 1);
  CHECK(value_of("position 0", m.vm) > 0);
}

TEST(expr_position_alone_is_still_a_label) {
  Machine m({I(Op::STOP)});
  tmcl::ProgramInfo info;
  info.labels = {{"position", 7}};
  CHECK_EQ(value_of("position", m.vm, info), 7);
  CHECK_EQ(value_of("position + 1", m.vm, info), 8);
}

TEST(expr_errors_say_where_and_suggest_a_name) {
  tmcl::ProgramInfo info;
  info.labels = {{"homing", 3}};
  tmcl::Expr e;
  std::string err;
  std::size_t at = 99;
  CHECK(!tmcl::parse_expr("acc + accc", info, e, err, &at));
  CHECK_EQ(err, "no register, label or constant named 'accc'; did you mean 'acc'? in 'acc + accc'");
  CHECK_EQ(at, 6u);
  CHECK(!tmcl::parse_expr("pc == homnig", info, e, err, &at));
  CHECK_EQ(err, "no register, label or constant named 'homnig'; did you mean 'homing'? in 'pc == homnig'");
  CHECK_EQ(at, 6u);
  CHECK(!tmcl::parse_expr("v[3", info, e, err, &at));
  CHECK_EQ(err, "missing ']' after v[... in 'v[3'");
  CHECK_EQ(at, 3u);
  CHECK(!tmcl::parse_expr("nosuch", info, e, err, &at));
  CHECK_EQ(err, "no register, label or constant named 'nosuch' in 'nosuch'");
  CHECK_EQ(at, 0u);
}

namespace {
// A machine that is not a VM (as tmclctl reads a module): values from a table, one read refused.
struct TableReader final : tmcl::ExprReader {
  int motors() const override { return 2; }
  bool reg(Reg r, std::int64_t& out, std::string& error) override {
    if (r == Steps) {
      error = "steps cannot be read from a module";
      return false;
    }
    out = r == Acc ? 5 : r == Pc ? 12 : 0;
    return true;
  }
  bool var(int n, std::int64_t& out, std::string&) override { return out = 100 + n, true; }
  bool axis(int param, int motor, std::int64_t& out, std::string&) override { return out = param * 10 + motor, true; }
  bool global(int bank, int param, std::int64_t& out, std::string&) override { return out = bank * 1000 + param, true; }
  bool port(int kind, int n, std::int64_t& out, std::string&) override {
    return out = (kind == tmcl::Expr::Node::Out ? 50 : 60) + n, true;
  }
};
}  // namespace

TEST(expr_reads_through_any_reader) {
  TableReader m;
  tmcl::ProgramInfo info;
  auto eval = [&](const std::string& text, std::int64_t& v, std::string& err) {
    tmcl::Expr e;
    CHECK(tmcl::parse_expr(text, info, e, err));
    return tmcl::eval_expr(e, m, v, err);
  };
  std::int64_t v = 0;
  std::string err;
  CHECK(eval("acc + v[3] + ap(4, 1) + gp(2, 7) + out(1) + in(2) + position 1 + velocity(0) + pc", v, err));
  CHECK_EQ(v, 5 + 103 + 41 + 2007 + 51 + 62 + 11 + 30 + 12);
  CHECK(!eval("steps > 0", v, err));
  CHECK_EQ(err, "steps cannot be read from a module");
  CHECK(!eval("ap(1, 2)", v, err));  // the reader has two motors
  CHECK_EQ(err, "motor 2 is out of range (0..1)");
}

TEST(expr_arithmetic_wraps_instead_of_overflowing) {
  Machine m({I(Op::STOP)});
  CHECK_EQ(value_of("(1 << 62) * 4", m.vm), 0);
  CHECK_EQ(value_of("(1 << 62) + (1 << 62) + (1 << 62) + (1 << 62)", m.vm), 0);
  CHECK_EQ(value_of("-(1 << 62) - (1 << 62) - (1 << 62) - (1 << 62)", m.vm), 0);
  CHECK_EQ(value_of("(-(1 << 62) - (1 << 62)) / -1", m.vm), INT64_MIN);
  CHECK_EQ(value_of("-(-(1 << 62) - (1 << 62))", m.vm), INT64_MIN);
  CHECK_EQ(value_of("(-(1 << 62) - (1 << 62)) % -1", m.vm), 0);
  CHECK_EQ(value_of("7 / -1 + 7 % -1", m.vm), -7);
}
