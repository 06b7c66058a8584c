// Test runner benchmarks (issue 27): 1,000 test files of one 500-line program run by
// `tmclrun --test` in one process, one at a time (-j 1) and two at a time (-j 2), against 1,000
// plain `tmclrun` runs of the same program one after another (a process each, as a script or a
// Makefile would run them); and the cost of --coverage against the same test run without it.
// Whole processes, wall time, the best of several rounds taken in turn (the machine is shared).
// Prints "figure<TAB>goal<TAB>measured" rows for tests/bench/run_all.sh.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "spawn.hpp"

namespace {

using tmcl::bench::run_process;

// 500 lines: a main loop calling 40 subroutines of 11 lines each, every one with arithmetic on
// the accumulator and a user variable, a comparison and a branch: 950,000 instructions and 19
// simulated seconds a run, about 2 ms of the VM's work (as much as starting a process costs).
std::string program() {
  std::string s = "// testrun_bench: a 500-line program\n        SGP 0, 2, 2000          // outer loop count\nouter:\n";
  for (int k = 0; k < 40; ++k) s += "        CSUB s" + std::to_string(k) + "\n";
  s += "        DJNZ 0, outer\n        STOP\n";
  for (int k = 0; k < 40; ++k) {
    const std::string n = std::to_string(k), low = "low" + n;
    s += "s" + n + ":     CALC ADD, " + std::to_string(k + 1) + "\n";
    s += "        CALCV ADD, 1, " + n + "\n";
    s += "        COMP 100000\n";
    s += "        JC LT, " + low + "\n";
    s += "        CALC SUB, 100000\n";
    s += low + ":  CALCV MOD, 1, 7919\n";
    s += "        CALCV ADD, 2, 1\n";
    s += "        CALC MUL, 3\n";
    s += "        CALC MOD, 1000003\n";
    s += "        CALCV SUB, 3, 1\n";
    s += "        RSUB\n";
  }
  while (std::count(s.begin(), s.end(), '\n') < 500) s += "// padding to 500 lines\n";
  return s;
}

std::string test_file(int i) {
  const int ms = 1 + i % 7;
  return "# test " + std::to_string(i) + "\nprogram ../prog.tmc\nmax-time 1min\n" + "at " + std::to_string(ms) +
         "ms input 0 = 1\nexpect at " + std::to_string(ms) + "ms v[0] <= 2000\nexpect at " + std::to_string(2 * ms) +
         "ms v[2] > 0\nexpect at end v[0] = 0\nexpect at end halted stop\nexpect never fault\nexpect no warnings\n";
}

}  // namespace

int main() {
  char tmpl[] = "/tmp/tmcl-testrun-bench-XXXXXX";
  const std::string dir = ::mkdtemp(tmpl);
  std::ofstream(dir + "/prog.tmc") << program();
  std::filesystem::create_directory(dir + "/tests");
  constexpr int kTests = 1000;
  for (int i = 0; i < kTests; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "/tests/t%04d.tmctest", i);
    std::ofstream(dir + name) << test_file(i);
  }
  const std::string run = TMCL_TMCLRUN_PATH, prog = dir + "/prog.tmc", tests = dir + "/tests";
  // The program and its tests must run and pass, or every figure is meaningless.
  if (run_process({run, prog}) < 0 || run_process({run, "--test", "-j", "1", tests}) < 0) {
    std::printf("testrun: the benchmark's program or tests failed\t-\tnot measured\n");
    return 1;
  }
  // Wall time (what a user waits for) and CPU time (steadier on a shared machine), best of each.
  struct Best {
    double wall = 1e9, cpu = 1e9;
    void add(double w, double c) {
      if (w < 0) return;
      wall = std::min(wall, w);
      cpu = std::min(cpu, c);
    }
  } plain, j1, j2, cov;
  for (int round = 0; round < 3; ++round) {
    double wall = 0, cpu = 0, c = 0;
    for (int i = 0; i < kTests && wall >= 0; ++i) {
      const double one = run_process({run, prog}, &c);
      wall = one < 0 ? -1 : wall + one;
      cpu += c;
    }
    plain.add(wall, cpu);
    double w = run_process({run, "--test", "-j", "1", tests}, &c);
    j1.add(w, c);
    w = run_process({run, "--test", "-j", "2", tests}, &c);
    j2.add(w, c);
    w = run_process({run, "--test", "-j", "1", "--coverage", dir + "/coverage.info", tests}, &c);
    cov.add(w, c);
  }
  std::filesystem::remove_all(dir);
  std::printf("testrun: 1,000 plain tmclrun runs of a 500-line program, one after another (s, wall / CPU)\t-\t%.2f / %.2f\n",
              plain.wall, plain.cpu);
  std::printf("testrun: 1,000 test files of that program, tmclrun --test -j 1 (s, wall / CPU)\t-\t%.2f / %.2f\n", j1.wall, j1.cpu);
  std::printf("testrun: the same, -j 2 (s, wall / CPU)\t-\t%.2f / %.2f\n", j2.wall, j2.cpu);
  std::printf("testrun: the same, -j 1 --coverage (s, wall / CPU)\t-\t%.2f / %.2f\n", cov.wall, cov.cpu);
  std::printf("testrun: -j 1 / 1,000 plain runs (wall)\t<= 1.1\t%.2f\n", j1.wall / plain.wall);
  std::printf("testrun: -j 2 / -j 1 (wall)\t<= 0.6\t%.2f\n", j2.wall / j1.wall);
  std::printf("testrun: --coverage / the same run without it (-j 1, wall; CPU)\t<= 1.2\t%.2f; %.2f\n", cov.wall / j1.wall,
              cov.cpu / j1.cpu);
  return 0;
}
