// Control-flow analysis benchmark (issue 13): assembling a generated program of about a million
// lines (blocks with a loop and a CSUB, 97 subroutines) with the analysis after the link, against
// the same assembly without it. Goal: at most 1.3 times as long. Two figures: in process, and
// what the goal is about, whole tmclasm processes (`tmclasm -o big.bin big.tmc` against
// `tmclasm --no-analysis -o big.bin big.tmc`), each the best of nine runs, the two interleaved;
// and for information the processes' CPU time, steadier than wall time on a loaded machine.
// Prints "figure<TAB>goal<TAB>measured" rows for bench/run_all.sh.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "spawn.hpp"

#include "tmcl/analysis.hpp"
#include "tmcl/asm/assembler.hpp"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kRuns = 9;  // best of nine, with and without interleaved: the machine is shared

std::string program(int lines) {
  std::string s;
  int n = 0, i = 0;
  for (; n < lines; ++i, n += 7) {
    std::string k = std::to_string(i);
    s += "// block " + k + "\nL" + k + ":\n  SAP 4, 0, " + std::to_string(i % 5000) + "\n  MVP ABS, 0, -" +
         std::to_string(i * 7) + "\n  WAIT POS, 0, 0\n  CSUB S" + std::to_string(i % 97) + "\n  JC GE, L" + k + "\n";
  }
  s += "STOP\n";
  for (int k = 0; k < 97; ++k) s += "S" + std::to_string(k) + ": CALC ADD, " + std::to_string(k) + "\n  RSUB\n";
  return s;
}

double cpu_now() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e6;
}

// Wall time of one assembly (and analysis), its CPU time in `cpu`.
double run(tmcl::MemoryReader& reader, bool analysis, double& cpu) {
  auto t0 = Clock::now();
  double c0 = cpu_now();
  tmcl::AsmOptions opts;
  // As tmclasm runs it: without label names, which it collects (assembling again) only when the
  // analysis has something to say, and this program is clean.
  opts.symbols = false;
  auto r = tmcl::assemble({"bench.tmc"}, opts, reader);
  if (analysis) {
    tmcl::analyze(tmcl::analysis_input(r), r.diags);
  }
  if (!r.ok() || r.diags.warning_count() != 0) std::fprintf(stderr, "%s", r.diags.render(r.sources).c_str());
  cpu = cpu_now() - c0;
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main() {
  const int lines = 1000000;
  tmcl::MemoryReader reader;
  reader.files["bench.tmc"] = program(lines);
  double without = 1e9, with = 1e9, cpu_without = 1e9, cpu_with = 1e9;
  for (int k = 0; k < kRuns; ++k) {
    double c = 0;
    without = std::min(without, run(reader, false, c));
    cpu_without = std::min(cpu_without, c);
    with = std::min(with, run(reader, true, c));
    cpu_with = std::min(cpu_with, c);
  }
  std::printf("tmclasm with the control-flow analysis, %d-line program, in process\t<= 1.3x without\t%.2fx (%.0f ms vs %.0f ms)\n",
              lines, with / without, with * 1e3, without * 1e3);
  std::printf("the same, CPU time (user + system)\t(info)\t%.2fx (%.0f ms vs %.0f ms)\n", cpu_with / cpu_without,
              cpu_with * 1e3, cpu_without * 1e3);

  // Whole processes, as a user runs them: start, read, assemble, analyse, write, exit.
  std::string dir = "/tmp/tmcl-analysis-bench-" + std::to_string(::getpid());
  std::string mkdir = "mkdir -p " + dir;
  if (std::system(mkdir.c_str()) != 0) return 1;
  std::ofstream(dir + "/big.tmc") << reader.files["bench.tmc"];
  double p_without = 1e9, p_with = 1e9, c_without = 1e9, c_with = 1e9;
  bool failed = false;
  for (int k = 0; k < kRuns && !failed; ++k) {
    double ca = 0, cb = 0;
    double a = tmcl::bench::run_process({TMCL_TMCLASM_PATH, "--no-analysis", "-o", dir + "/big.bin", dir + "/big.tmc"}, &ca);
    double b = tmcl::bench::run_process({TMCL_TMCLASM_PATH, "-o", dir + "/big.bin", dir + "/big.tmc"}, &cb);
    failed = a < 0 || b < 0;
    p_without = std::min(p_without, a);
    p_with = std::min(p_with, b);
    c_without = std::min(c_without, ca);
    c_with = std::min(c_with, cb);
  }
  std::string rm = "rm -rf " + dir;
  if (std::system(rm.c_str()) != 0) return 1;
  if (failed) {
    std::fprintf(stderr, "analysis_bench: %s did not assemble the program\n", TMCL_TMCLASM_PATH);
    return 1;
  }
  std::printf("tmclasm with the control-flow analysis, %d-line program, whole process\t<= 1.3x without\t%.2fx (%.0f ms vs %.0f ms)\n",
              lines, p_with / p_without, p_with * 1e3, p_without * 1e3);
  std::printf("the same, CPU time (user + system) of the processes\t(info)\t%.2fx (%.0f ms vs %.0f ms)\n",
              c_with / c_without, c_with * 1e3, c_without * 1e3);
  return 0;
}
