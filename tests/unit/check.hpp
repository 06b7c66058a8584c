// Our small unit-test harness: TEST(name) { CHECK(...); CHECK_EQ(a, b); } and one main per
// executable (define TMCL_TEST_MAIN in exactly one file). Prints a failure with file:line and
// both values, and a closing "N passed, N failed" line; exits non-zero on any failure.
#pragma once

#include <cstdio>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace tmcl_test {

struct Case {
  const char* name;
  std::function<void()> fn;
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
  Register(const char* name, std::function<void()> fn) { registry().push_back({name, std::move(fn)}); }
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

inline void fail(const char* file, int line, const std::string& what) {
  ++failures();
  std::fprintf(stderr, "%s:%d: check failed: %s\n", file, line, what.c_str());
}

}  // namespace tmcl_test

#define TMCL_CAT2(a, b) a##b
#define TMCL_CAT(a, b) TMCL_CAT2(a, b)
#define TEST(name)                                                                     \
  static void name();                                                                  \
  static ::tmcl_test::Register TMCL_CAT(tmcl_reg_, name)(#name, name);                 \
  static void name()

#define CHECK(cond)                                                 \
  do {                                                              \
    if (!(cond)) ::tmcl_test::fail(__FILE__, __LINE__, #cond);       \
  } while (0)

#define CHECK_EQ(a, b)                                                                     \
  do {                                                                                     \
    const ::tmcl_test::Compared tmcl_c_ = ::tmcl_test::compare_eq((a), (b));               \
    if (!tmcl_c_.equal)                                                                    \
      ::tmcl_test::fail(__FILE__, __LINE__,                                                \
                        std::string(#a " == " #b "\n    left:  ") + tmcl_c_.left +          \
                            "\n    right: " + tmcl_c_.right);                               \
  } while (0)

#ifdef TMCL_TEST_MAIN
int main(int argc, char** argv) {
  int passed = 0, failed = 0;
  for (auto& c : ::tmcl_test::registry()) {
    if (argc > 1 && std::string(argv[1]) != c.name) continue;
    int before = ::tmcl_test::failures();
    c.fn();
    if (::tmcl_test::failures() == before) {
      ++passed;
    } else {
      ++failed;
      std::fprintf(stderr, "FAILED: %s\n", c.name);
    }
  }
  std::printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 && passed > 0 ? 0 : 1;
}
#endif
