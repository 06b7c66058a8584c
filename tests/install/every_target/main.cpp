// The every-target consumer's program (tests/install/every_target/CMakeLists.txt): configuring,
// compiling and linking it is the test; it runs to show the installed profiles are there.
#include <cstdio>

#include "tmcl/profile.hpp"
#include "tmcl/version.hpp"

int main() {
  const tmcl::Profile* module = tmcl::find_profile("tmcm-1110");
  std::printf("every_target: tmcl %s, tmcm-1110 %s\n", tmcl::kVersion, module ? "found" : "missing");
  return module ? 0 : 1;
}
