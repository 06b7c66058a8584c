// Control-flow analysis benchmark (issue 13): assembling a generated program of about a million
// lines (blocks with a loop and a CSUB, 97 subroutines) with the analysis after the link, against
// the same assembly without it. Goal: at most 1.3 times as long. Two figures: in process (best of
// three), and what the goal is about, whole tmclasm processes (`tmclasm -o big.bin big.tmc`
// against `tmclasm --no-analysis -o big.bin big.tmc`, interleaved, best of seven).
// Prints "figure<TAB>goal<TAB>measured" rows for bench/run_all.sh.
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

double run(tmcl::MemoryReader& reader, bool analysis) {
  auto t0 = Clock::now();
  tmcl::AsmOptions opts;
  // As tmclasm runs it: without label names, which it collects (assembling again) only when the
  // analysis has something to say, and this program is clean.
  opts.symbols = false;
  auto r = tmcl::assemble({"bench.tmc"}, opts, reader);
  if (analysis) {
    tmcl::AnalysisInput in;
    in.program = r.program;
    in.lines = r.lines;
    in.sources = &r.sources;
    in.profile = r.profile;
    in.appended_stop = r.appended_stop;
    in.targets_checked = true;
    tmcl::analyze(in, r.diags);
  }
  if (!r.ok() || r.diags.warning_count() != 0) std::fprintf(stderr, "%s", r.diags.render(r.sources).c_str());
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main() {
  const int lines = 1000000;
  tmcl::MemoryReader reader;
  reader.files["bench.tmc"] = program(lines);
  double without = 1e9, with = 1e9;
  for (int k = 0; k < 3; ++k) {
    without = std::min(without, run(reader, false));
    with = std::min(with, run(reader, true));
  }
  std::printf("tmclasm with the control-flow analysis, %d-line program, in process\t<= 1.3x without\t%.2fx (%.0f ms vs %.0f ms)\n",
              lines, with / without, with * 1e3, without * 1e3);

  // Whole processes, as a user runs them: start, read, assemble, analyse, write, exit.
  std::string dir = "/tmp/tmcl-analysis-bench-" + std::to_string(::getpid());
  std::string mkdir = "mkdir -p " + dir;
  if (std::system(mkdir.c_str()) != 0) return 1;
  std::ofstream(dir + "/big.tmc") << reader.files["bench.tmc"];
  double p_without = 1e9, p_with = 1e9;
  bool failed = false;
  for (int k = 0; k < 7 && !failed; ++k) {
    double a = tmcl::bench::run_process({TMCL_TMCLASM_PATH, "--no-analysis", "-o", dir + "/big.bin", dir + "/big.tmc"});
    double b = tmcl::bench::run_process({TMCL_TMCLASM_PATH, "-o", dir + "/big.bin", dir + "/big.tmc"});
    failed = a < 0 || b < 0;
    p_without = std::min(p_without, a);
    p_with = std::min(p_with, b);
  }
  std::string rm = "rm -rf " + dir;
  if (std::system(rm.c_str()) != 0) return 1;
  if (failed) {
    std::fprintf(stderr, "analysis_bench: %s did not assemble the program\n", TMCL_TMCLASM_PATH);
    return 1;
  }
  std::printf("tmclasm with the control-flow analysis, %d-line program, whole process\t<= 1.3x without\t%.2fx (%.0f ms vs %.0f ms)\n",
              lines, p_with / p_without, p_with * 1e3, p_without * 1e3);
  return 0;
}
