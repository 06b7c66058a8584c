// The core of our unit-test harness (tests/unit/check.hpp, which tests include): the registry of
// TEST cases, CHECK and CHECK_EQ.
#pragma once

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace tmcl_test {

struct Case {
  const char* name;
  void (*fn)();
  const char* file;  // __FILE__ of the TEST, for `--file STEM` (tmcl_unit_suite in tests/CMakeLists.txt)
};

inline std::vector<Case>& registry() {
  static std::vector<Case> cases;
  return cases;
}
inline int& failures() {
  static int n = 0;
  return n;
}

struct Register {
  Register(const char* name, void (*fn)(), const char* file) { registry().push_back({name, fn, file}); }
};

template <typename T>
std::string show(const T& v) {
  std::ostringstream os;
  if constexpr (requires { os << v; })
    os << v;
  else
    os << "<value>";
  return os.str();
}

// Compares inside the full expression that made its operands, so an operand that refers into a
// temporary (`CHECK_EQ(parse(x).name(), "a")`) is still alive when it is compared and shown.
struct Compared {
  bool equal;
  std::string left, right;
};
template <typename A, typename B>
Compared compare_eq(const A& a, const B& b) {
  if (a == b) return {true, {}, {}};
  return {false, show(a), show(b)};
}

// Whether a TEST of file `file` belongs to the source file named `stem` (its name without folder
// and extension): a suite of several files runs one file's cases as one CTest test.
inline bool from_file(const char* file, const std::string& stem) {
  std::string f = file;
  const auto slash = f.find_last_of('/');
  if (slash != std::string::npos) f.erase(0, slash + 1);
  const auto dot = f.rfind('.');
  if (dot != std::string::npos) f.erase(dot);
  return f == stem;
}

inline void fail(const char* file, int line, const std::string& what) {
  ++failures();
  std::fprintf(stderr, "%s:%d: check failed: %s\n", file, line, what.c_str());
}

// Out of line from the macro, so a CHECK_EQ costs one call, not a string expression, per site.
inline void fail_eq(const char* file, int line, const char* what, const Compared& c) {
  fail(file, line, std::string(what) + "\n    left:  " + c.left + "\n    right: " + c.right);
}

}  // namespace tmcl_test

#define TMCL_CAT2(a, b) a##b
#define TMCL_CAT(a, b) TMCL_CAT2(a, b)
#define TEST(name)                                                                     \
  static void name();                                                                  \
  static ::tmcl_test::Register TMCL_CAT(tmcl_reg_, name)(#name, name, __FILE__);       \
  static void name()

#define CHECK(cond)                                                 \
  do {                                                              \
    if (!(cond)) ::tmcl_test::fail(__FILE__, __LINE__, #cond);       \
  } while (0)

#define CHECK_EQ(a, b)                                                                     \
  do {                                                                                     \
    const ::tmcl_test::Compared tmcl_c_ = ::tmcl_test::compare_eq((a), (b));               \
    if (!tmcl_c_.equal) ::tmcl_test::fail_eq(__FILE__, __LINE__, #a " == " #b, tmcl_c_);   \
  } while (0)
