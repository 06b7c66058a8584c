// tmclctl PORT debug --probe: the report of tmcl/host/debug_probe.hpp, printed. Kept out of
// tmclctl.cpp, which only parses the command line. `debug` with a program (the debugger on the
// module, issue 39) is not part of this file.
#pragma once

#include <csignal>
#include <cstdint>
#include <string>
#include <vector>

#include "tmcl/host/client.hpp"
#include "tmcl/profile.hpp"

// Runs the probe on the module behind `client` (module address `module`, profile `profile`, whose
// program memory bounds the read past the end) and prints the report on standard output.
// Returns the exit status: 0 done, 2 the module refused a command the probe needs, 69 no reply,
// 74 port error, 130 interrupted (`*stop` set by Ctrl-C; the program is still put back, `*stop`
// cleared for it).
int tmclctl_debug_probe(tmcl::host::Client& client, const tmcl::Profile& profile, int module, volatile std::sig_atomic_t* stop);
