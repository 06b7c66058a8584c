// The one main() of the VM unit tests (tests/unit/check.hpp).
#define TMCL_TEST_MAIN
#include "check.hpp"
