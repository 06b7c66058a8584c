// The one main() of every unit-test executable (tests/unit/check.hpp); tmcl_test_main in
// tests/CMakeLists.txt adds it, compiled on its own, outside the tests' unity unit.
#define TMCL_TEST_MAIN
#include "check.hpp"
