// `tmclctl PORT debug --probe` (issue 39): what a module's firmware does where the manuals are
// silent and a debugger on the module depends on it — the application status (135) after reset,
// while running, inside a WAIT and after a stop; 130 across a WAIT and a CSUB; whether a direct
// GAP while stopped changes the accumulator; what 134 answers past the end of program memory.
// A small probe program is loaded for it; the module's own program is read first (134) and put
// back and verified afterwards, also when the probe fails half-way if the module still answers.
// The result is a report to paste into an issue, with the choices the debugger makes on that
// module. The virtual module has each behaviour as a switch (tmclrun --variant, errata S24-S27).
#pragma once

#include <functional>
#include <string>

#include "tmcl/host/transfer.hpp"

namespace tmcl::host {

struct DebugProbeOptions {
  std::string module;  // how the report names the module ("address 1, firmware 0015V114 (...)")
  int memory = 0;      // program memory in instructions (0: unknown; 134 past the end is not tried)
  int wait_ticks = 100;  // the probe program's WAIT TICKS, 10 ms each
  // Where the module's program is written (a TMCL-IDE .bin) when it cannot be put back.
  std::string rescue_path = "tmclctl-probe-saved.bin";
  // Called before the program is put back: a front end clears its Ctrl-C flag here, so that an
  // interrupted probe still restores (nullptr: nothing).
  std::function<void()> before_restore;
};

struct DebugProbeResult {
  Outcome outcome = Outcome::Ok;
  std::string message;  // what failed, and whether the module's program was put back
  std::string report;   // what was found, as far as the probe got
};

DebugProbeResult debug_probe(Client& client, const DebugProbeOptions& options);

}  // namespace tmcl::host
