// Debugger benchmarks (issue 14). (1) The dispatch loop of vm_bench (CALC ADD / DJNZ, a timer
// interrupt on) run plainly by the VM, then by the debugging engine with 10 breakpoints and a
// watchpoint on a user variable that are never hit: the engine's cost must stay within 10%.
// (2) reverse-step after 10^9 executed instructions must answer within 100 ms, with the
// checkpoint memory within its default bound (64 MiB). (3) The dispatch loop in the slices of
// tmclrun --dap (a poll between two) and how long one slice takes. (4) The same loop as whole
// processes: `tmclrun prog.tmc` against `tmclrun --debug-commands` with the 10 breakpoints and the
// watchpoint, then `run`, by CPU time, best of five (issue 26: at most 1.10x). The rest measures wall time.
// Prints "figure<TAB>goal<TAB>measured" rows for tests/bench/run_all.sh.
#include <poll.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <vector>

#include "spawn.hpp"
#include "tmcl/debugger.hpp"
#include "programs.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/vm.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using tmcl::Instruction;
using tmcl::Op;
using tmcl::bench::I;

// iterations of CALC ADD, 1 / DJNZ 0; timer 0 every second; ten instructions after STOP that
// never run (where the breakpoints go) and a handler that counts in v[1].
std::vector<Instruction> dispatch_program(std::int32_t iterations) {
  std::vector<Instruction> p = {I(Op::SGP, 0, 2, iterations), I(Op::VECT, 0, 0, 9), I(Op::SGP, 0, 3, 1000), I(Op::EI, 0),
                                I(Op::EI, 255), I(Op::CALC, 0, 0, 1), I(Op::DJNZ, 0, 0, 5), I(Op::STOP), I(Op::STOP),
                                I(Op::CALCV, 0, 1, 1), I(Op::RETI)};
  for (int i = 0; i < 10; ++i) p.push_back(I(Op::CALCV, 0, 2, 1));
  p.push_back(I(Op::STOP));
  return p;
}

double plain_ns(const std::vector<Instruction>& prog) {
  auto core = tmcl::make_ideal_motion_core();
  tmcl::Vm vm(*tmcl::find_profile("generic"), *core);
  vm.load(prog);
  vm.power_on(nullptr);
  vm.start(0);
  auto t0 = Clock::now();
  vm.run({});
  return std::chrono::duration<double>(Clock::now() - t0).count() * 1e9 / static_cast<double>(vm.steps);
}

std::unique_ptr<tmcl::debug::Engine> engine(const std::vector<Instruction>& prog) {
  tmcl::debug::Setup s;
  s.profile = tmcl::find_profile("generic");
  s.core_name = "ideal";
  tmcl::debug::ProgramInfo info;
  info.program = prog;
  return std::make_unique<tmcl::debug::Engine>(s, info, tmcl::make_ideal_motion_core());
}

}  // namespace

int main() {
  const auto prog = dispatch_program(100'000'000);
  double best_plain = 1e9, best_debug = 1e9;
  for (int round = 0; round < 3; ++round) {
    best_plain = std::min(best_plain, plain_ns(prog));
    auto e = engine(prog);
    for (int i = 0; i < 10; ++i) e->add_breakpoint(11 + i, "*", false);
    std::string err;
    e->add_watchpoint("v[2]", err);
    auto t0 = Clock::now();
    tmcl::debug::Stop st = e->start(false);
    double ns = std::chrono::duration<double>(Clock::now() - t0).count() * 1e9 / static_cast<double>(e->vm().steps);
    if (st.kind != tmcl::debug::StopKind::Exited) std::printf("debug run did not end with STOP!\n");
    best_debug = std::min(best_debug, ns);
  }
  std::printf("debugger: dispatch loop, plain VM (ns per instruction)\t-\t%.3f\n", best_plain);
  std::printf("debugger: dispatch loop, 10 breakpoints + watch v[2] not hit (ns per instruction)\t-\t%.3f\n", best_debug);
  std::printf("debugger: cost of unhit breakpoints and watchpoint (%% of run time)\t<= 10\t%.1f\n",
              (best_debug / best_plain - 1.0) * 100.0);

  // The run as tmclrun --dap makes it: in slices, polling the requests' descriptor (a pipe with
  // nothing in it) between two slices. The slice bounds how long a pause waits.
  int fds[2];
  if (::pipe(fds) != 0) return 1;
  double best_sliced = 1e9;
  for (int round = 0; round < 3; ++round) {
    auto e = engine(prog);
    e->on_slice = [&] {
      pollfd p{fds[0], POLLIN, 0};
      ::poll(&p, 1, 0);
      return tmcl::kNever;
    };
    auto t0 = Clock::now();
    e->start(false);
    best_sliced = std::min(best_sliced, std::chrono::duration<double>(Clock::now() - t0).count() * 1e9 / static_cast<double>(e->vm().steps));
  }
  std::printf("debugger: dispatch loop in DAP slices polling a pipe (ns per instruction)\t-\t%.3f\n", best_sliced);
  std::printf("debugger: cost of the slices (%% of run time)\t-\t%.1f\n", (best_sliced / best_plain - 1.0) * 100.0);
  std::printf("debugger: one slice of %llu instructions, the longest a DAP pause waits (ms)\t-\t%.3f\n",
              static_cast<unsigned long long>(tmcl::debug::Setup{}.slice_steps),
              best_sliced * static_cast<double>(tmcl::debug::Setup{}.slice_steps) / 1e6);
  ::close(fds[0]);
  ::close(fds[1]);

  // reverse-step after 10^9 instructions (5e8 iterations of the two-instruction loop).
  auto e = engine(dispatch_program(500'000'000));
  auto t0 = Clock::now();
  tmcl::debug::Stop st = e->start(false);
  double run_s = std::chrono::duration<double>(Clock::now() - t0).count();
  std::uint64_t steps = e->vm().steps;
  double worst_ms = 0;
  for (int i = 0; i < 5; ++i) {
    auto r0 = Clock::now();
    st = e->reverse_step(1);
    worst_ms = std::max(worst_ms, std::chrono::duration<double>(Clock::now() - r0).count() * 1e3);
  }
  bool ok = st.kind == tmcl::debug::StopKind::Step && e->vm().steps == steps - 5;
  std::printf("debugger: run of %.2e instructions with checkpoints (s)\t-\t%.2f\n", static_cast<double>(steps), run_s);
  std::printf("debugger: reverse-step after 1e9 instructions, worst of 5 (ms)\t<= 100\t%.1f%s\n", worst_ms, ok ? "" : " (wrong state!)");
  std::printf("debugger: checkpoint memory after 1e9 instructions (MiB, bound 64)\t<= 64\t%.1f (%zu checkpoints)\n",
              static_cast<double>(e->checkpoint_memory()) / (1 << 20), e->checkpoint_count());

  // Whole processes: the dispatch loop (6e8 instructions) as tmclrun runs it, and under the
  // debugger with 10 breakpoints and a watchpoint never hit; best of three each, interleaved.
  char dir_template[] = "/tmp/debug_bench_XXXXXX";
  const char* dir = ::mkdtemp(dir_template);
  if (!dir) return 1;
  const std::string source = std::string(dir) + "/loop.tmc", cmds = std::string(dir) + "/run.cmds";
  std::ofstream(source) << "        SGP 0, 2, 300000000\n        VECT 0, Tick\n        SGP 0, 3, 1000\n        EI 0\n"
                         "        EI 255\nLoop:   CALC ADD, 1\n        DJNZ 0, Loop\n        STOP\n"
                         "Never:  CALCV ADD, 2, 1\n        CALCV ADD, 2, 1\n        CALCV ADD, 2, 1\n        CALCV ADD, 2, 1\n"
                         "        CALCV ADD, 2, 1\n        CALCV ADD, 2, 1\n        CALCV ADD, 2, 1\n        CALCV ADD, 2, 1\n"
                         "        CALCV ADD, 2, 1\n        CALCV ADD, 2, 1\n        STOP\nTick:   CALCV ADD, 1, 1\n        RETI\n";
  {
    std::ofstream c(cmds);
    for (int i = 0; i < 10; ++i) c << "break *Never+" << i << "\n";
    c << "watch v[2]\nrun\n";
  }
  // CPU time (user + system) of each process: on the shared machine steadier than wall time.
  double plain_s = 1e9, debug_s = 1e9, plain_wall = 1e9, debug_wall = 1e9;
  for (int round = 0; round < 5; ++round) {
    double ca = 0, cb = 0;
    double a = tmcl::bench::run_process({TMCL_TMCLRUN_PATH, source}, &ca);
    double b = tmcl::bench::run_process({TMCL_TMCLRUN_PATH, "--debug-commands", cmds, source}, &cb);
    if (a < 0 || b < 0) {
      std::fprintf(stderr, "debug_bench: %s did not run the program\n", TMCL_TMCLRUN_PATH);
      return 1;
    }
    plain_s = std::min(plain_s, ca);
    debug_s = std::min(debug_s, cb);
    plain_wall = std::min(plain_wall, a);
    debug_wall = std::min(debug_wall, b);
  }
  std::printf("debugger: tmclrun --debug against tmclrun, 6e8 instructions, whole process (CPU time)\t<= 1.10x\t%.2fx (%.0f ms vs %.0f ms; wall %.0f ms vs %.0f ms)\n",
              debug_s / plain_s, debug_s * 1e3, plain_s * 1e3, debug_wall * 1e3, plain_wall * 1e3);
  std::remove(source.c_str());
  std::remove(cmds.c_str());
  ::rmdir(dir);
  return 0;
}
