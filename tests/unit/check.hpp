// Our small unit-test harness: TEST(name) { CHECK(...); CHECK_EQ(a, b); } and one main per
// executable (define TMCL_TEST_MAIN in exactly one file). Prints a failure with file:line and
// both values, and a closing "N passed, N failed" line; exits non-zero on any failure.
// `EXE [--file STEM] [CASE]` runs only the cases of source file STEM (a suite of several test
// files, tmcl_unit_suite in tests/CMakeLists.txt) and only the case named CASE.
// The harness is check_core.hpp; this file adds main(). It has no include guard of its own, so a
// unity build (several test files compiled as one unit, tests/CMakeLists.txt) still gets main()
// from the file that defines TMCL_TEST_MAIN, wherever that file falls in the unit. A suite
// defines TMCL_TEST_NO_MAIN for its test files and takes main() from tests/unit/test_main.cpp.
#include "check_core.hpp"

#if defined(TMCL_TEST_MAIN) && !defined(TMCL_TEST_MAIN_DONE) && !defined(TMCL_TEST_NO_MAIN)
#define TMCL_TEST_MAIN_DONE
int main(int argc, char** argv) {
  std::string file, only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--file" && i + 1 < argc) {
      file = argv[++i];
    } else {
      only = a;
    }
  }
  int passed = 0, failed = 0;
  for (auto& c : ::tmcl_test::registry()) {
    if (!file.empty() && !::tmcl_test::from_file(c.file, file)) continue;
    if (!only.empty() && only != c.name) continue;
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
