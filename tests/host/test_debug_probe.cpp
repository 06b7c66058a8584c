// tmclctl PORT debug --probe beyond its golden cases (tests/golden/tmclctl/debug-probe*.run):
// Ctrl-C in the middle still puts the module's program back; a module with no program gets none
// back (the end marker at address 0).
#include <algorithm>

#include "check.hpp"
#include "tmclctl_test.hpp"

using namespace hosttest;

namespace {

const char* kModuleProgram = "SAP 4, 0, 1000\nloop: GAP 1, 0\nJA loop\n";

}  // namespace

TEST(debug_probe_ctrl_c_puts_the_program_back) {
  // SIGINT goes once the server's log shows the first 130 (the probe is then stepping through its
  // WAIT, its own program on the module), not after a fixed time a loaded machine may spend first.
  const std::string log = temp_dir() + "/probe-ctrl-c.log";
  const std::string src = write_temp("probe-module.tmc", kModuleProgram);
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd", "--trace", "--log", log, src});
  const std::string before = temp_dir() + "/probe-before.bin", after = temp_dir() + "/probe-after.bin";
  CHECK_EQ(ctl({server.port(), "upload", "-o", before}).status, 0);
  Output d = hosttest::run({kCtl, "--timeout", "5s", server.port(), "debug", "--probe"}, 60000, 0, [&](pid_t pid) {
    if (!has(slurp(log), "130 StepApplication")) return false;
    ::kill(pid, SIGINT);
    return true;
  });
  CHECK_EQ(d.status, 130);
  CHECK(has(d.err, "the module's program (4 instructions) is back, verified with 134"));
  CHECK(has(d.out, "tmcl debug probe"));
  CHECK_EQ(ctl({server.port(), "upload", "-o", after}).status, 0);
  CHECK(slurp(before) == slurp(after));
  CHECK_EQ(slurp(after).size(), 32u);  // the three and the STOP the assembler appends
}

TEST(debug_probe_on_a_module_without_a_program) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  Output d = ctl({server.port(), "debug", "--probe"}, 60000);
  show(d);
  CHECK_EQ(d.status, 0);
  CHECK(has(d.out, "module's program: 0 instructions"));
  CHECK(has(d.out, "the module's program (0 instructions) is back, verified with 134"));
  const std::string after = temp_dir() + "/probe-empty.bin";
  Output u = ctl({server.port(), "upload", "-o", after});
  CHECK_EQ(u.status, 0);
  CHECK(has(u.out, "read 0 instructions"));
}
