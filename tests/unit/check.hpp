// Our small unit-test harness: TEST(name) { CHECK(...); CHECK_EQ(a, b); }. Prints a failure with
// file:line and both values, and a closing "N passed, N failed" line; exits non-zero on any
// failure. `EXE [--file STEM] [CASE]` runs only the cases of source file STEM (a suite of several
// test files, tmcl_unit_suite in tests/CMakeLists.txt) and only the case named CASE.
// The harness is check_core.hpp; this file adds main() where TMCL_TEST_MAIN is defined, which is
// tests/unit/test_main.cpp alone: tmcl_test_main in tests/CMakeLists.txt links it into every
// unit-test executable.
#include "check_core.hpp"

#ifdef TMCL_TEST_MAIN
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
