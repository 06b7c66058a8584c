// Entry point of the motion test executables (tests/unit/check.hpp).
#define TMCL_TEST_MAIN
#include "check.hpp"
