// tmclctl PORT test FILE|DIR...: the test runner (cli/testrun) on a real or virtual module, over
// the host protocol (cli/host). Kept out of tmclctl.cpp, which only parses the command line.
#pragma once

#include <csignal>
#include <string>
#include <vector>

#include "tmcl/host/client.hpp"
#include "tmcl/profile.hpp"

// Runs the test files and folders `paths` on the module behind `client` (module profile `profile`,
// which `target` names as -t takes it: -t as given, or the identified module's name) and prints a
// line per test and the closing line; writes a JUnit report to `junit` unless empty. Returns the
// exit status of the tests: 0 every test passed, 1 a test failed, 65 a bad test file or program,
// 74 a report not written, 130 interrupted (`*stop` set by Ctrl-C). When the module fell silent or
// the port failed, `failed` says how (the run stopped there; tmclctl exits 69/74 for it), else it
// is Fail::None.
int tmclctl_test(tmcl::host::Client& client, const tmcl::Profile& profile, const std::string& target,
                 const std::vector<std::string>& paths, const std::vector<std::string>& include_dirs, const std::string& junit,
                 volatile std::sig_atomic_t* stop, tmcl::host::Fail& failed);
