// Debugging on a module (issue 39), measured against `tmclrun --serve tcp` with the host client
// (cli/host) and the raw command sequences the debugger sends: round trips per step, per
// breakpoint hit and per `print`, counted exactly (the client's request counter); steps per
// second; the time from a breakpoint hit to the stop report. Times are also given as ratios to a
// bare round trip (135 type 1) on the same connection in the same run, the figure that stays
// stable on a loaded machine. Best of 7 interleaved rounds. docs/performance.md has the figures.
//
// The sequences (docs/tmclctl.md, `debug --probe`; issue 39 §2):
//   step:        130, 135/1 (where it stopped)
//   stop report: 135/2, 135/3 (A and X, before any direct read)
//   print v[N]:  GGP N, 2
//   hit:         129 (continue), 135/1 polls until the pc is the breakpoint's (the JA to itself
//                spins there), 128, 132 + the instruction + 133 (put back), stop report;
//                continuing: 130 (over the instruction), 132 + JA + 133 (the patch again)
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "tmcl/host/client.hpp"
#include "tmcl/host/port.hpp"
#include "tmcl/host/transfer.hpp"
#include "spawn.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using tmcl::Instruction;
using tmcl::Op;
namespace host = tmcl::host;

Instruction make(Op op, int type = 0, int motor = 0, std::int32_t value = 0) {
  return Instruction{static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), value};
}

struct Bench {
  host::Client& c;
  bool ok = true;
  std::int32_t ask(const Instruction& ins) {
    const host::Result r = c.request(ins, false);
    if (!r.ok() || (r.reply.status != host::kStatusOk && r.reply.status != host::kStatusLoaded)) {
      std::fprintf(stderr, "onmodule_bench: %s: %s\n", c.describe(ins).c_str(), r.ok() ? "error status" : r.error.c_str());
      ok = false;
    }
    return r.reply.value;
  }
  int pc() { return static_cast<int>(static_cast<std::uint32_t>(ask(make(Op::GetApplicationStatus, 1))) & 0xFFFF); }
  void write(int at, const Instruction& ins) {
    ask(make(Op::EnterDownloadMode, 0, 0, at));
    ask(ins);
    ask(make(Op::ExitDownloadMode));
  }
  void stop_report() {
    ask(make(Op::GetApplicationStatus, 2));
    ask(make(Op::GetApplicationStatus, 3));
  }
};

// The program: a counting loop; the breakpoint is on its first instruction.
constexpr int kBreak = 0;
const std::vector<Instruction> kProgram{make(Op::CALC, 0, 0, 1),  // 0: CALC ADD, 1
                                        make(Op::JA, 0, 0, 0)};   // 1: JA 0

}  // namespace

int main() {
  // A served USB-2-SD on loopback TCP (any free port). Simulated time runs 1000 times the wall
  // clock, so that the program is at its breakpoint before the first poll: the round trips
  // counted are the debugger's, not the wall clock's.
  std::string line;
  const pid_t server = tmcl::bench::start_server({TMCL_TMCLRUN, "--serve", "tcp:127.0.0.1:0", "-t", "usb-2-sd",
                                                  "--max-wall-time", "300s", "--time-scale", "1000"},
                                                 line);
  const std::string prefix = "listening on ";
  const std::string spec = "tcp:" + (line.rfind(prefix, 0) == 0 ? line.substr(prefix.size()) : line);
  if (server < 0 || line.rfind(prefix, 0) != 0) {
    std::fprintf(stderr, "onmodule_bench: cannot start tmclrun --serve tcp\n");
    return 1;
  }
  std::string err;
  auto port = host::Port::open(spec, 9600, 1000, err);
  if (!port) {
    std::fprintf(stderr, "onmodule_bench: %s\n", err.c_str());
    return 1;
  }
  host::Client client(*port, {});
  Bench b{client};
  if (host::download(client, kProgram, 0, 577, {}).outcome != host::Outcome::Ok) return 1;
  b.ask(make(Op::ResetApplication));

  constexpr int kBare = 2000, kSteps = 1000, kHits = 200, kPrints = 2000;
  double bare = 1e9, step = 1e9, hit = 1e9, report = 1e9, print = 1e9;
  double rt_step = 0, rt_hit = 0, rt_print = 0;
  const Instruction jump_to_itself = make(Op::JA, 0, 0, kBreak);
  for (int round = 0; round < 7 && b.ok; ++round) {
    auto t0 = Clock::now();
    for (int i = 0; i < kBare; ++i) b.ask(make(Op::GetApplicationStatus, 1));
    bare = std::min(bare, std::chrono::duration<double>(Clock::now() - t0).count() / kBare);

    // Stepping: 130, then where it stopped.
    b.ask(make(Op::StopApplication));
    std::uint64_t n0 = client.stats().requests;
    t0 = Clock::now();
    for (int i = 0; i < kSteps; ++i) {
      b.ask(make(Op::StepApplication));
      (void)b.pc();
    }
    step = std::min(step, std::chrono::duration<double>(Clock::now() - t0).count() / kSteps);
    rt_step = static_cast<double>(client.stats().requests - n0) / kSteps;

    // Breakpoint hits: patched, continued, detected, stopped, put back, reported, stepped over.
    b.ask(make(Op::StopApplication));
    b.write(kBreak, jump_to_itself);
    n0 = client.stats().requests;
    double hit_total = 0, report_total = 0;
    for (int i = 0; i < kHits; ++i) {
      t0 = Clock::now();
      b.ask(make(Op::RunApplication));  // continue (129 type 0)
      while (b.ok && b.pc() != kBreak) {
      }
      const auto seen = Clock::now();
      b.ask(make(Op::StopApplication));
      b.write(kBreak, kProgram[kBreak]);
      b.stop_report();
      const auto reported = Clock::now();
      b.ask(make(Op::StepApplication));  // continuing: over the instruction, then the patch again
      b.write(kBreak, jump_to_itself);
      hit_total += std::chrono::duration<double>(Clock::now() - t0).count();
      report_total += std::chrono::duration<double>(reported - seen).count();
    }
    hit = std::min(hit, hit_total / kHits);
    report = std::min(report, report_total / kHits);
    rt_hit = static_cast<double>(client.stats().requests - n0) / kHits;
    b.ask(make(Op::StopApplication));
    b.write(kBreak, kProgram[kBreak]);

    // print v[0]: GGP 0, 2.
    n0 = client.stats().requests;
    t0 = Clock::now();
    for (int i = 0; i < kPrints; ++i) b.ask(make(Op::GGP, 0, 2));
    print = std::min(print, std::chrono::duration<double>(Clock::now() - t0).count() / kPrints);
    rt_print = static_cast<double>(client.stats().requests - n0) / kPrints;
  }
  port.reset();
  ::kill(server, SIGTERM);
  int st;
  ::waitpid(server, &st, 0);
  if (!b.ok) return 1;
  std::printf("on-module debugging: bare round trip (135) over TCP, us\t(info)\t%.1f\n", bare * 1e6);
  std::printf("on-module debugging: round trips per step (130, 135/1)\t2\t%.2f\n", rt_step);
  std::printf("on-module debugging: steps per second over TCP\t(info)\t%.0f\n", 1.0 / step);
  std::printf("on-module debugging: step / bare round trip\t<= 2.5\t%.2f\n", step / bare);
  std::printf("on-module debugging: round trips per breakpoint hit, continue to continue\t12\t%.2f\n", rt_hit);
  std::printf("on-module debugging: breakpoint hit, continue to continue, us\t(info)\t%.1f\n", hit * 1e6);
  std::printf("on-module debugging: hit seen to stop report (128, put back, A, X), us\t(info)\t%.1f\n", report * 1e6);
  std::printf("on-module debugging: hit seen to stop report (6 round trips) / bare round trip\t(info)\t%.2f\n", report / bare);
  std::printf("on-module debugging: round trips per print v[N] (GGP)\t1\t%.2f\n", rt_print);
  std::printf("on-module debugging: print / bare round trip\t<= 1.3\t%.2f\n", print / bare);
  return 0;
}
