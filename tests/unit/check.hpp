// Our small unit-test harness: TEST(name) { CHECK(...); CHECK_EQ(a, b); } and one main per
// executable (define TMCL_TEST_MAIN in exactly one file). Prints a failure with file:line and
// both values, and a closing "N passed, N failed" line; exits non-zero on any failure.
// The harness is check_core.hpp; this file adds main(). It has no include guard of its own, so a
// unity build (several test files compiled as one unit, tests/CMakeLists.txt) still gets main()
// from the file that defines TMCL_TEST_MAIN, wherever that file falls in the unit.
#include "check_core.hpp"

#if defined(TMCL_TEST_MAIN) && !defined(TMCL_TEST_MAIN_DONE)
#define TMCL_TEST_MAIN_DONE
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
