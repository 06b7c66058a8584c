// The one main() of a suite of test files (tmcl_unit_suite in tests/CMakeLists.txt), whose files
// are compiled with TMCL_TEST_NO_MAIN; this file is compiled on its own, outside their unit.
#undef TMCL_TEST_NO_MAIN
#define TMCL_TEST_MAIN
#include "check.hpp"
