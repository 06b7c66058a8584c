// The debugger's expressions (print, display, set var, conditions, watchpoints): a small
// recursive-descent parser into a node vector, evaluated on the live VM. Reads of parameters go
// through the VM's own access rules, so the debugger can never show a value the module would not.
#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "tmcl/diag_text.hpp"
#include "tmcl/duration.hpp"
#include "tmcl/expr.hpp"

namespace tmcl {
namespace {

// A Reg node's value: which register ExprReader reads.
enum Reg : std::int64_t {
  kA = ExprReader::Acc, kX = ExprReader::X, kFlags = ExprReader::Flags, kErrors = ExprReader::Errors,
  kPc = ExprReader::Pc, kSp = ExprReader::Sp, kTime = ExprReader::Time, kSteps = ExprReader::Steps
};

struct RegName {
  const char* name;
  Reg reg;
};
constexpr RegName kRegs[] = {{"a", kA}, {"acc", kA}, {"x", kX}, {"flags", kFlags}, {"errors", kErrors},
                             {"pc", kPc}, {"sp", kSp}, {"time", kTime}, {"steps", kSteps}};

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

class Parser {
 public:
  Parser(const std::string& text, const ProgramInfo& info, Expr& out) : s_(text), info_(info), e_(out) {}

  bool parse(std::string& error, std::size_t* error_at) {
    int root = binary(0);
    skip();
    if (err_.empty() && pos_ < s_.size()) fail("unexpected '" + character() + "'");
    if (!err_.empty()) {
      error = err_ + " in '" + s_ + "'";
      if (error_at) *error_at = std::min(err_at_, s_.size());
      return false;
    }
    e_.root = root;
    e_.text = s_;
    return true;
  }

 private:
  // Binary operators by precedence level, loosest first (C's order).
  static constexpr const char* kLevels[][4] = {{"||"}, {"&&"}, {"|"}, {"^"}, {"&"}, {"==", "!="},
                                               {"<=", ">=", "<", ">"}, {"<<", ">>"}, {"+", "-"}, {"*", "/", "%"}};
  static constexpr int kLevelCount = 10;

  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool eat(const char* tok) {
    skip();
    std::string t = tok;
    if (s_.compare(pos_, t.size(), t) != 0) return false;
    // "<" must not take the first half of "<<" or "<="; "|" not of "||"; "&" not of "&&".
    if (t.size() == 1 && pos_ + 1 < s_.size()) {
      char n = s_[pos_ + 1];
      if ((t == "<" || t == ">") && (n == t[0] || n == '=')) return false;
      if ((t == "|" || t == "&") && n == t[0]) return false;
      if (t == "!" && n == '=') return false;
    }
    pos_ += t.size();
    return true;
  }
  // The first error wins; `at` is where it is (default: the current position).
  // The character at pos_, whole when it is valid UTF-8 (a stray "±"), else its one byte.
  std::string character() const {
    const std::size_t n = static_cast<unsigned char>(s_[pos_]) >= 0x80 ? utf8_length(s_, pos_) : 1;
    return s_.substr(pos_, std::max<std::size_t>(n, 1));
  }

  void fail(std::string m, std::size_t at = std::string::npos) {
    if (!err_.empty()) return;
    err_ = std::move(m);
    err_at_ = at == std::string::npos ? pos_ : at;
  }
  int node(Expr::Node n) {
    e_.nodes.push_back(n);
    return static_cast<int>(e_.nodes.size() - 1);
  }
  static std::int64_t op_code(const char* op) { return static_cast<std::int64_t>(op[0]) * 256 + (op[1] ? op[1] : 0); }

  int binary(int level) {
    if (level == kLevelCount) return unary();
    skip();
    const std::size_t start = pos_;
    int left = binary(level + 1);
    for (;;) {
      if (!err_.empty()) return left;
      const char* hit = nullptr;
      for (const char* op : kLevels[level])
        if (op && eat(op)) {
          hit = op;
          break;
        }
      if (!hit) return left;
      int right = binary(level + 1);
      left = node({Expr::Node::Binary, op_code(hit), left, right, static_cast<std::uint32_t>(start),
                   static_cast<std::uint32_t>(std::max(pos_, start) - start)});
    }
  }

  // Nesting deeper than this is refused, not a stack overflow.
  static constexpr int kMaxDepth = 100;

  int unary() {
    if (++depth_ > kMaxDepth) {
      fail("expression nested too deeply (more than " + std::to_string(kMaxDepth) + " levels)");
      pos_ = s_.size();
      return -1;
    }
    struct Leave {
      int& d;
      ~Leave() { --d; }
    } leave{depth_};
    skip();
    const std::size_t start = pos_;
    int i = -1;
    bool op_found = false;
    for (const char* op : {"-", "~", "!"})
      if (!op_found && eat(op)) i = node({Expr::Node::Unary, op_code(op), unary(), -1}), op_found = true;
    if (!op_found) i = eat("+") ? unary() : primary();
    if (i >= 0) {
      auto& n = e_.nodes[static_cast<std::size_t>(i)];
      n.at = static_cast<std::uint32_t>(start);
      n.len = static_cast<std::uint32_t>(std::max(pos_, start) - start);
    }
    return i;
  }

  std::vector<int> args(std::size_t n, const std::string& what) {
    std::vector<int> out;
    if (!eat("(")) {
      fail(what + " needs " + std::to_string(n) + " argument" + (n > 1 ? "s" : "") + " in parentheses");
      return out;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (i && !eat(",")) fail(what + " needs " + std::to_string(n) + " arguments");
      out.push_back(binary(0));
    }
    if (!eat(")")) fail("missing ')' after the arguments of " + what);
    while (out.size() < n) out.push_back(-1);
    return out;
  }

  int primary() {
    skip();
    if (pos_ >= s_.size()) {
      fail("expression ends too early");
      return -1;
    }
    char c = s_[pos_];
    if (eat("(")) {
      int inner = binary(0);
      if (!eat(")")) fail("missing ')'");
      return inner;
    }
    if (std::isdigit(static_cast<unsigned char>(c))) return number();
    if (c == '$') {
      // $pc, $sp, $acc, $x ... name registers, as gdb's do. $N is the command line's value
      // history (expanded before the expression gets here); hexadecimal is written 0x1F, not as
      // the assembler's $1F: $a, $acc would be registers and $ab a number.
      const std::size_t dollar = pos_;
      std::size_t start = ++pos_;
      while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
      const std::string written = s_.substr(start, pos_ - start);
      std::string name = lower(written);
      for (const auto& r : kRegs)
        if (name == r.name) return node({Expr::Node::Reg, r.reg, -1, -1});
      const bool hex = std::all_of(name.begin(), name.end(), [](char h) { return std::isxdigit(static_cast<unsigned char>(h)); });
      fail(name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))
               ? "'$" + name + "' is no register (the value history $, $N is print's; hexadecimal is written 0x...)"
               : "no register named '$" + name + "' ($pc, $sp, $acc, $x, $flags, $errors, $time, $steps)" +
                     (hex ? "; hexadecimal is written 0x" + written : ""),
           dollar);
      return -1;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t start = pos_;
      while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
      std::string name = s_.substr(start, pos_ - start);
      std::string low = lower(name);
      if (low == "v") {
        if (!eat("[")) {
          fail("v needs an index: v[5]");
          return -1;
        }
        int index = binary(0);
        if (!eat("]")) fail("missing ']' after v[...");
        return node({Expr::Node::Var, 0, index, -1});
      }
      struct Fn {
        const char* name;
        Expr::Node::Kind kind;
        std::size_t n;
      };
      static constexpr Fn kFns[] = {{"ap", Expr::Node::Ap, 2}, {"gp", Expr::Node::Gp, 2}, {"in", Expr::Node::In, 1},
                                    {"ain", Expr::Node::Ain, 1}, {"out", Expr::Node::Out, 1}};
      skip();
      for (const auto& f : kFns)
        if (low == f.name && pos_ < s_.size() && s_[pos_] == '(') {
          auto a = args(f.n, name);
          return node({f.kind, 0, a[0], f.n > 1 ? a[1] : -1});
        }
      for (const auto& r : kRegs)
        if (low == r.name) return node({Expr::Node::Reg, r.reg, -1, -1});
      // `position M` and `velocity M`: the actual position (axis parameter 1) and actual speed
      // (3) of motor M, the words a test's expectations read best with.
      if ((low == "position" || low == "velocity") && pos_ < s_.size() &&
          (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '(' || s_[pos_] == '_' || s_[pos_] == '$')) {
        int param = node({Expr::Node::Num, low == "position" ? 1 : 3, -1, -1});
        int motor = unary();
        return node({Expr::Node::Ap, 0, param, motor});
      }
      if (auto v = info_.symbol(name)) return node({Expr::Node::Num, *v, -1, -1});
      fail("no register, label or constant named '" + name + "'" + suggestion(name), start);
      return -1;
    }
    fail("unexpected '" + character() + "'");
    return -1;
  }

  int number() {
    std::size_t start = pos_;
    std::int64_t v = 0;
    int base = 10;
    if (s_.compare(pos_, 2, "0x") == 0 || s_.compare(pos_, 2, "0X") == 0) {
      base = 16;
      pos_ += 2;
    } else if (s_.compare(pos_, 2, "0b") == 0 || s_.compare(pos_, 2, "0B") == 0) {
      base = 2;
      pos_ += 2;
    }
    std::size_t digits = pos_;
    while (pos_ < s_.size() && std::isxdigit(static_cast<unsigned char>(s_[pos_]))) {
      int d = std::isdigit(static_cast<unsigned char>(s_[pos_])) ? s_[pos_] - '0' : std::tolower(s_[pos_]) - 'a' + 10;
      if (d >= base) break;
      v = v * base + d;
      if (v > (std::int64_t{1} << 40)) {
        fail("number too large");
        return -1;
      }
      ++pos_;
    }
    if (pos_ == digits) {
      fail("bad number");
      return -1;
    }
    // A duration: 2s, 1.5ms, 1min (in microseconds, like `time`).
    if (base == 10 && pos_ < s_.size() && (std::isalpha(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '.')) {
      while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '.')) ++pos_;
      std::string text = s_.substr(start, pos_ - start), err;
      auto d = parse_duration(text, err);
      if (!d) {
        fail(err);
        return -1;
      }
      v = *d;
    }
    return node({Expr::Node::Num, v, -1, -1});
  }

  // "; did you mean 'acc'?" when a register, function, label or constant is close to `name`.
  std::string suggestion(const std::string& name) const {
    std::vector<std::string_view> names = {"v", "ap", "gp", "in", "ain", "out", "position", "velocity"};
    for (const auto& r : kRegs) names.emplace_back(r.name);
    for (const auto& l : info_.labels) names.emplace_back(l.first);
    for (const auto& c : info_.constants) names.emplace_back(c.first);
    std::string hint = closest_match(name, names);
    return hint.empty() ? "" : "; did you mean '" + hint + "'?";
  }

  const std::string& s_;
  const ProgramInfo& info_;
  Expr& e_;
  std::size_t pos_ = 0;
  std::size_t err_at_ = 0;
  int depth_ = 0;
  std::string err_;
};

std::int64_t op(const char* s) { return static_cast<std::int64_t>(s[0]) * 256 + (s[1] ? s[1] : 0); }

// The VM as expressions read it: parameters through its own access rules, so the debugger can
// never show a value the module would not.
class VmReader final : public ExprReader {
 public:
  explicit VmReader(Vm& vm) : vm_(vm) {}
  int motors() const override { return vm_.profile->motors; }
  bool reg(Reg r, std::int64_t& out, std::string&) override {
    switch (r) {
      case Acc: out = vm_.acc; break;
      case X: out = vm_.x; break;
      case Flags: out = vm_.flags; break;
      case Errors: out = vm_.errors; break;
      case Pc: out = vm_.pc; break;
      case Sp: out = vm_.sp; break;
      case Time: out = vm_.now; break;
      case Steps: out = static_cast<std::int64_t>(vm_.steps); break;
    }
    return true;
  }
  bool var(int n, std::int64_t& out, std::string&) override {
    out = vm_.vars[static_cast<std::size_t>(n)];
    return true;
  }
  bool axis(int param, int motor, std::int64_t& out, std::string& error) override {
    std::int32_t v = 0;
    if (vm_.get_axis(motor, param, v) != kStatusOk) {
      error = "axis parameter " + std::to_string(param) + " cannot be read on " + std::string(vm_.profile->name);
      return false;
    }
    out = v;
    return true;
  }
  bool global(int bank, int param, std::int64_t& out, std::string& error) override {
    std::int32_t v = 0;
    if (vm_.get_global(bank, param, v) != kStatusOk) {
      error = "global parameter " + std::to_string(param) + " of bank " + std::to_string(bank) + " cannot be read on " +
              std::string(vm_.profile->name);
      return false;
    }
    out = v;
    return true;
  }
  bool port(int kind, int n, std::int64_t& out, std::string&) override {
    auto p = static_cast<std::size_t>(n);
    out = kind == Expr::Node::In ? vm_.inputs[p] : kind == Expr::Node::Ain ? vm_.analog[p] : vm_.outputs[p];
    return true;
  }

 private:
  Vm& vm_;
};

bool eval_node(const Expr& e, int i, ExprReader& m, std::int64_t& out, std::string& error);

// a + b, a - b, a * b in 64 bits, wrapping around as the module's 32-bit arithmetic does instead
// of overflowing (a test file's expectation may multiply anything).
std::int64_t wrap(std::int64_t a, std::int64_t b, char o) {
  const auto x = static_cast<std::uint64_t>(a), y = static_cast<std::uint64_t>(b);
  return static_cast<std::int64_t>(o == '+' ? x + y : o == '-' ? x - y : x * y);
}

bool index_arg(const Expr& e, int i, ExprReader& m, std::int64_t lo, std::int64_t hi, const char* what, std::int64_t& out,
               std::string& error) {
  if (!eval_node(e, i, m, out, error)) return false;
  if (out < lo || out > hi) {
    error = std::string(what) + " " + std::to_string(out) + " is out of range (" + std::to_string(lo) + ".." +
            std::to_string(hi) + ")";
    return false;
  }
  return true;
}

bool eval_node(const Expr& e, int i, ExprReader& m, std::int64_t& out, std::string& error) {
  const Expr::Node& n = e.nodes[static_cast<std::size_t>(i)];
  std::int64_t a = 0, b = 0;
  switch (n.kind) {
    case Expr::Node::Num: out = n.value; return true;
    case Expr::Node::Reg: return m.reg(static_cast<ExprReader::Reg>(n.value), out, error);
    case Expr::Node::Var:
      if (!index_arg(e, n.a, m, 0, 255, "user variable", a, error)) return false;
      return m.var(static_cast<int>(a), out, error);
    case Expr::Node::Ap:
      if (!index_arg(e, n.a, m, 0, 255, "axis parameter", a, error)) return false;
      if (!index_arg(e, n.b, m, 0, m.motors() - 1, "motor", b, error)) return false;
      return m.axis(static_cast<int>(a), static_cast<int>(b), out, error);
    case Expr::Node::Gp:
      if (!index_arg(e, n.a, m, 0, 255, "bank", a, error)) return false;
      if (!index_arg(e, n.b, m, 0, 255, "global parameter", b, error)) return false;
      return m.global(static_cast<int>(a), static_cast<int>(b), out, error);
    case Expr::Node::In:
    case Expr::Node::Ain:
    case Expr::Node::Out:
      if (!index_arg(e, n.a, m, 0, Vm::kPorts - 1, "port", a, error)) return false;
      return m.port(n.kind, static_cast<int>(a), out, error);
    case Expr::Node::Unary:
      if (!eval_node(e, n.a, m, a, error)) return false;
      out = n.value == op("-") ? wrap(0, a, '-') : n.value == op("~") ? ~a : !a;
      return true;
    case Expr::Node::Binary: {
      if (!eval_node(e, n.a, m, a, error)) return false;
      // && and || do not evaluate their right side when the left decides.
      if (n.value == op("&&") && !a) return out = 0, true;
      if (n.value == op("||") && a) return out = 1, true;
      if (!eval_node(e, n.b, m, b, error)) return false;
      const std::int64_t o = n.value;
      if ((o == op("/") || o == op("%")) && b == 0) {
        error = "division by zero";
        return false;
      }
      if (o == op("+")) out = wrap(a, b, '+');
      else if (o == op("-")) out = wrap(a, b, '-');
      else if (o == op("*")) out = wrap(a, b, '*');
      else if (o == op("/")) out = b == -1 ? wrap(0, a, '-') : a / b;  // INT64_MIN / -1 wraps too
      else if (o == op("%")) out = b == -1 ? 0 : a % b;
      else if (o == op("&")) out = a & b;
      else if (o == op("|")) out = a | b;
      else if (o == op("^")) out = a ^ b;
      else if (o == op("<<")) out = (b < 0 || b > 62) ? 0 : a << b;
      else if (o == op(">>")) out = (b < 0 || b > 62) ? (a < 0 ? -1 : 0) : a >> b;
      else if (o == op("<")) out = a < b;
      else if (o == op(">")) out = a > b;
      else if (o == op("<=")) out = a <= b;
      else if (o == op(">=")) out = a >= b;
      else if (o == op("==")) out = a == b;
      else if (o == op("!=")) out = a != b;
      else if (o == op("&&")) out = b != 0;
      else out = b != 0;  // ||
      return true;
    }
  }
  return false;
}

}  // namespace

bool Expr::uses_time() const {
  for (const auto& n : nodes)
    if ((n.kind == Node::Reg && n.value == kTime) || n.kind == Node::Ap || n.kind == Node::Gp || n.kind == Node::In ||
        n.kind == Node::Ain)
      return true;
  return false;
}

bool Expr::assignable() const {
  if (root < 0) return false;
  auto k = nodes[static_cast<std::size_t>(root)].kind;
  if (k == Node::Reg) {
    auto r = nodes[static_cast<std::size_t>(root)].value;
    return r == kA || r == kX || r == kFlags || r == kErrors;
  }
  return k == Node::Var || k == Node::Ap || k == Node::Gp || k == Node::Out;
}

bool parse_expr(const std::string& text, const ProgramInfo& info, Expr& out, std::string& error, std::size_t* error_at) {
  out = Expr{};
  return Parser(text, info, out).parse(error, error_at);
}

bool eval_expr(const Expr& e, ExprReader& reader, std::int64_t& value, std::string& error) {
  if (e.root < 0) {
    error = "empty expression";
    return false;
  }
  return eval_node(e, e.root, reader, value, error);
}

bool eval_expr(const Expr& e, Vm& vm, std::int64_t& value, std::string& error) {
  VmReader reader(vm);
  return eval_expr(e, reader, value, error);
}

namespace {
// Why the VM refused a value, when it is the range (the profile's, as for a program's SAP).
std::string out_of(const ParamInfo* p) { return p ? ": outside its range, " + range_text(*p) : ""; }
}  // namespace

bool assign_expr(const Expr& e, Vm& vm, std::int64_t value, std::string& error) {
  if (!e.assignable()) {
    error = "'" + e.text + "' cannot be assigned (use A, X, flags, errors, v[n], ap(p, m), gp(bank, n), out(n), in(n) or ain(n))";
    return false;
  }
  if (value < INT32_MIN || value > UINT32_MAX) {
    error = std::to_string(value) + " does not fit 32 bits";
    return false;
  }
  auto v32 = static_cast<std::int32_t>(static_cast<std::uint32_t>(value));
  const Expr::Node& n = e.nodes[static_cast<std::size_t>(e.root)];
  VmReader reader(vm);
  std::int64_t a = 0, b = 0;
  switch (n.kind) {
    case Expr::Node::Reg:
      if (n.value == kA) vm.acc = v32;
      else if (n.value == kX) vm.x = v32;
      else if (n.value == kFlags) vm.flags = static_cast<std::uint8_t>(v32);
      else vm.errors = static_cast<std::uint8_t>(v32);
      return true;
    case Expr::Node::Var:
      if (!index_arg(e, n.a, reader, 0, 255, "user variable", a, error)) return false;
      vm.vars[static_cast<std::size_t>(a)] = v32;
      return true;
    case Expr::Node::Ap:
      if (!index_arg(e, n.a, reader, 0, 255, "axis parameter", a, error)) return false;
      if (!index_arg(e, n.b, reader, 0, vm.profile->motors - 1, "motor", b, error)) return false;
      if (vm.set_axis(static_cast<int>(b), static_cast<int>(a), v32) != kStatusOk) {
        error = "axis parameter " + std::to_string(a) + " cannot be set to " + std::to_string(v32) + " on " +
                std::string(vm.profile->name) + out_of(vm.range_refusing(true, 0, static_cast<int>(a), v32));
        return false;
      }
      return true;
    case Expr::Node::Gp:
      if (!index_arg(e, n.a, reader, 0, 255, "bank", a, error)) return false;
      if (!index_arg(e, n.b, reader, 0, 255, "global parameter", b, error)) return false;
      if (vm.set_global(static_cast<int>(a), static_cast<int>(b), v32) != kStatusOk) {
        error = "global parameter " + std::to_string(b) + " of bank " + std::to_string(a) + " cannot be set to " +
                std::to_string(v32) + " on " + std::string(vm.profile->name) +
                out_of(vm.range_refusing(false, static_cast<int>(a), static_cast<int>(b), v32));
        return false;
      }
      return true;
    default:
      if (!index_arg(e, n.a, reader, 0, Vm::kPorts - 1, "port", a, error)) return false;
      vm.outputs[static_cast<std::size_t>(a)] = v32 != 0;
      return true;
  }
}

}  // namespace tmcl
