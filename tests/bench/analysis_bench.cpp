// Control-flow analysis benchmark (issues 13, 28 and 35): assembling a generated program of about
// a million lines with the analysis after the link, against the same assembly without it. Goal:
// at most 1.3 times as long. Three shapes: "blocks" (blocks with a loop and a CSUB, 97
// subroutines, clean), "subroutines" (a subroutine every ten lines: 100,000 subroutines in chains
// of 50 calls, 110,001 labels, CSUB and JC throughout, and 83,333 stretches of unreachable code,
// each a -Wunreachable warning) and "calls" (call-dense code with no RSUB, a label every ten
// instructions; below). Two figures each: in process, and what the goal is about, whole tmclasm
// processes (`tmclasm -o big.bin big.tmc` against `tmclasm --no-analysis -o big.bin big.tmc`),
// each the best of nine runs, the two interleaved; and for information the processes' CPU time,
// steadier than wall time on a loaded machine. On "calls", in the same run, assembly alone
// against GNU as on its x86 peer, the same program line for line (goal: at least 5 times as fast). For
// information, a fourth shape, "chain": one chain of 100,000 nested calls (the deepest call
// chain; it once took 167 s and 20 GB), as whole processes. (Peak memory is not measured here: a
// child started by posix_spawn reports the benchmark's own as its peak; docs/performance.md
// gives the command.)
// Prints "figure<TAB>goal<TAB>measured" rows for tests/bench/run_all.sh. `analysis_bench --program SHAPE
// [N]` prints a shape's program instead (N: lines, or calls for "chain"), to time or profile a
// tool on it by hand (docs/performance.md); `--x86-peer SHAPE [N]` prints its x86 peer, GNU as's file.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "programs.hpp"
#include "spawn.hpp"

#include "tmcl/analysis.hpp"
#include "tmcl/asm/assembler.hpp"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kRuns = 9;  // best of nine, with and without interleaved: the machine is shared

// The "blocks" shape: 1,000,201 lines, 714,486 instructions, 142,955 labels, no warning.
std::string blocks(int lines) {
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

// The "subroutines" shape: a main program calling the head of every chain, then 100,000
// subroutines of ten lines each. A subroutine counts in a global parameter (GGP/CALC/AGP),
// loops back with JC while the count is high, calls the next subroutine of its chain (chains of
// 50: the main program's deepest chain is 50 calls, one -Wcall-depth) and returns; in five of
// six the RSUB comes before a move and a WAIT nothing reaches (one -Wunreachable each). Every
// tenth subroutine has a second label, its loop's.
std::string subroutines(int lines) {
  const int n = lines / 10, chain = 50;
  std::string s = "Main:\n";
  for (int h = 0; h < n; h += chain) s += "  CSUB S" + std::to_string(h) + "\n";
  s += "  STOP\n";
  for (int k = 0; k < n; ++k) {
    std::string name = "S" + std::to_string(k), loop = k % 10 == 0 ? "T" + std::to_string(k / 10) : name;
    s += name + ":\n  GGP 0, 2\n" + (k % 10 == 0 ? loop + ": " : std::string("  ")) + "CALC ADD, 1\n  AGP 0, 2\n  COMP 1000\n  JC GE, " +
         loop + "\n" + ((k + 1) % chain != 0 && k + 1 < n ? "  CSUB S" + std::to_string(k + 1) + "\n" : std::string("  CALC SUB, 1\n"));
    s += k % 6 != 0 ? "  RSUB\n  MVP REL, 0, 100\n  WAIT TICKS, 0, 1\n" : "  MVP REL, 0, 100\n  WAIT TICKS, 0, 1\n  RSUB\n";
  }
  return s;
}

// The "calls" shape (issue 35): call-dense code with no RSUB. A constant line, then instructions
// cycling through twelve (SAP, GAP, CALC, COMP, JC GE to the label seven ahead, CALCV, MVP ABS,
// WAIT POS, CSUB to the label seven ahead, AGP, CALCX, SGP with an expression), every tenth with
// a label in front; v is the instruction's index mod 100,000, labels wrap around. At 1,100,001
// lines: 1,100,000 instructions, 110,000 labels; nothing returns, so each CSUB's subroutine runs
// on into the next: 91,666 -Wunreachable, one -Wrsub, -Wrecursion and -Wstack-leak each, nearly
// all beyond --error-limit.
std::string calls(int lines) {
  const int labels = (lines - 1) / 10;
  std::string s = "Speed = 100\n";
  s.reserve(static_cast<std::size_t>(lines) * 16);
  int i = 0;
  for (int k = 0; k < labels; ++k) {
    const std::string target = "L" + std::to_string((k + 7) % labels);
    for (int j = 0; j < 10; ++j, ++i) {
      const std::string v = std::to_string(i % 100000);
      s += j == 0 ? "L" + std::to_string(k) + ": " : std::string("  ");
      switch (i % 12) {
        case 0: s += "SAP 4, 0, " + v + "\n"; break;
        case 1: s += "GAP 1, 0\n"; break;
        case 2: s += "CALC ADD, " + v + "\n"; break;
        case 3: s += "COMP " + v + "\n"; break;
        case 4: s += "JC GE, " + target + "\n"; break;
        case 5: s += "CALCV SUB, 3, " + v + "\n"; break;
        case 6: s += "MVP ABS, 0, " + v + "\n"; break;
        case 7: s += "WAIT POS, 0, 0\n"; break;
        case 8: s += "CSUB " + target + "\n"; break;
        case 9: s += "AGP 7, 2\n"; break;
        case 10: s += "CALCX SWAP\n"; break;
        default: s += "SGP 9, 2, Speed*2+" + v + "\n"; break;
      }
    }
  }
  return s;
}

// The "chain" shape: the main program calls S0, each subroutine Sk calls S(k+1), the last
// returns: `calls` nested calls, one -Wcall-depth warning.
std::string chain(int calls) {
  std::string s = "Main:\n  CSUB S0\n  STOP\n";
  for (int k = 0; k < calls; ++k)
    s += "S" + std::to_string(k) + ":\n" + (k + 1 < calls ? "  CSUB S" + std::to_string(k + 1) + "\n" : std::string()) + "  RSUB\n";
  return s;
}

double cpu_now() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e6;
}

// Wall time of one assembly (and analysis), its CPU time in `cpu`. As tmclasm runs it: without
// label names when there is no analysis, with them for the analysis' messages, which are
// rendered (the stderr a user reads).
double run(tmcl::MemoryReader& reader, bool analysis, int warnings, double& cpu) {
  auto t0 = Clock::now();
  double c0 = cpu_now();
  tmcl::AsmOptions opts;
  opts.symbols = analysis;
  auto r = tmcl::assemble({"bench.tmc"}, opts, reader);
  r.diags.set_kind_limit(opts.error_limit);
  if (analysis) tmcl::analyze(tmcl::analysis_input(r), r.diags);
  std::string text = r.diags.render(r.sources, opts.error_limit);
  if (!r.ok() || r.diags.warning_count() != (analysis ? warnings : 0)) std::fprintf(stderr, "%s", text.c_str());
  cpu = cpu_now() - c0;
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Whole tmclasm processes on `text`, with and without the analysis: the best of kRuns each,
// interleaved.
struct Processes {
  double without = 1e9, with = 1e9, cpu_without = 1e9, cpu_with = 1e9;
};
bool processes(const std::string& text, Processes& p) {
  std::string dir = "/tmp/tmcl-analysis-bench-" + std::to_string(::getpid());
  std::string mkdir = "mkdir -p " + dir;
  if (std::system(mkdir.c_str()) != 0) return false;
  std::ofstream(dir + "/big.tmc") << text;
  bool failed = false;
  for (int k = 0; k < kRuns && !failed; ++k) {
    double ca = 0, cb = 0;
    double a = tmcl::bench::run_process({TMCL_TMCLASM_PATH, "--no-analysis", "-o", dir + "/big.bin", dir + "/big.tmc"}, &ca);
    double b = tmcl::bench::run_process({TMCL_TMCLASM_PATH, "-o", dir + "/big.bin", dir + "/big.tmc"}, &cb);
    failed = a < 0 || b < 0;
    p.without = std::min(p.without, a);
    p.with = std::min(p.with, b);
    p.cpu_without = std::min(p.cpu_without, ca);
    p.cpu_with = std::min(p.cpu_with, cb);
  }
  std::string rm = "rm -rf " + dir;
  if (std::system(rm.c_str()) != 0) return false;
  if (failed) std::fprintf(stderr, "analysis_bench: %s did not assemble the program\n", TMCL_TMCLASM_PATH);
  return !failed;
}

// Prints the four rows of one shape; false when tmclasm failed.
bool measure(const char* shape, const std::string& text, int warnings) {
  const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  tmcl::MemoryReader reader;
  reader.files["bench.tmc"] = text;
  double without = 1e9, with = 1e9, cpu_without = 1e9, cpu_with = 1e9;
  for (int k = 0; k < kRuns; ++k) {
    double c = 0;
    without = std::min(without, run(reader, false, warnings, c));
    cpu_without = std::min(cpu_without, c);
    with = std::min(with, run(reader, true, warnings, c));
    cpu_with = std::min(cpu_with, c);
  }
  std::printf("tmclasm with the control-flow analysis, %d-line program (%s), in process\t<= 1.3x without\t%.2fx (%.0f ms vs %.0f ms)\n",
              lines, shape, with / without, with * 1e3, without * 1e3);
  std::printf("the same, CPU time (user + system)\t(info)\t%.2fx (%.0f ms vs %.0f ms)\n", cpu_with / cpu_without,
              cpu_with * 1e3, cpu_without * 1e3);

  // Whole processes, as a user runs them: start, read, assemble, analyse, write, exit.
  Processes p;
  if (!processes(text, p)) return false;
  std::printf("tmclasm with the control-flow analysis, %d-line program (%s), whole process\t<= 1.3x without\t%.2fx (%.0f ms vs %.0f ms)\n",
              lines, shape, p.with / p.without, p.with * 1e3, p.without * 1e3);
  std::printf("the same, CPU time (user + system) of the processes\t(info)\t%.2fx (%.0f ms vs %.0f ms)\n",
              p.cpu_with / p.cpu_without, p.cpu_with * 1e3, p.cpu_without * 1e3);
  return true;
}

// Assembly alone (tmclasm --no-analysis) of `text` against GNU as on its x86 peer (the same
// program line for line, programs.hpp), whole processes, interleaved, the median of kRuns each: the reference run that says
// whether assembling stays fast on this shape (goal: at least 5 times as fast as GNU as).
bool versus_gnu_as(const char* shape, const std::string& text) {
  const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  std::string dir = "/tmp/tmcl-analysis-bench-as-" + std::to_string(::getpid());
  std::string mkdir = "mkdir -p " + dir;
  if (std::system(mkdir.c_str()) != 0) return false;
  std::ofstream(dir + "/big.tmc") << text;
  std::ofstream(dir + "/big.s") << tmcl::bench::x86_peer(text);
  std::vector<double> as, tmclasm;
  for (int k = 0; k < kRuns; ++k) {
    as.push_back(tmcl::bench::run_process({"as", "-o", dir + "/big.o", dir + "/big.s"}));
    tmclasm.push_back(tmcl::bench::run_process({TMCL_TMCLASM_PATH, "--no-analysis", "-o", dir + "/big.bin", dir + "/big.tmc"}));
  }
  std::string rm = "rm -rf " + dir;
  if (std::system(rm.c_str()) != 0) return false;
  std::sort(as.begin(), as.end());
  std::sort(tmclasm.begin(), tmclasm.end());
  if (tmclasm.front() < 0) {
    std::fprintf(stderr, "analysis_bench: %s did not assemble the program\n", TMCL_TMCLASM_PATH);
    return false;
  }
  const double a = as[kRuns / 2], t = tmclasm[kRuns / 2];
  if (as.front() < 0)
    std::printf("tmclasm --no-analysis vs GNU as on its x86 peer, %d-line program (%s), whole process\t>= 5x faster\tGNU as not available\n", lines, shape);
  else
    std::printf("tmclasm --no-analysis vs GNU as on its x86 peer, %d-line program (%s), whole process, medians\t>= 5x faster\t%.1fx (tmclasm %.0f ms, %.2fe6 lines/s; as %.0f ms, %.2fe6 lines/s)\n",
                lines, shape, a / t, t * 1e3, lines / t / 1e6, a * 1e3, lines / a / 1e6);
  return true;
}

// One chain of `calls` nested calls, whole processes, with the analysis and without
// (information: the cost must stay linear, not reach the 167 s it once took).
bool measure_chain(int calls) {
  Processes p;
  if (!processes(chain(calls), p)) return false;
  std::printf("tmclasm with the control-flow analysis, one chain of %d nested calls, whole process\t(info)\t%.0f ms (without: %.0f ms; CPU %.0f ms and %.0f ms)\n",
              calls, p.with * 1e3, p.without * 1e3, p.cpu_with * 1e3, p.cpu_without * 1e3);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 3 && (std::string(argv[1]) == "--program" || std::string(argv[1]) == "--x86-peer")) {
    const std::string shape = argv[2];
    const int n = argc > 3 ? std::atoi(argv[3]) : shape == "chain" ? 100000 : 1000000;
    if (n <= 0 || (shape != "blocks" && shape != "subroutines" && shape != "calls" && shape != "chain")) {
      std::fprintf(stderr, "usage: analysis_bench [--program|--x86-peer blocks|subroutines|calls|chain [N]]\n");
      return 2;
    }
    const std::string program = shape == "blocks"        ? blocks(n)
                                : shape == "subroutines" ? subroutines(n)
                                : shape == "calls"       ? calls(n)
                                                         : chain(n);
    std::fputs((std::string(argv[1]) == "--program" ? program : tmcl::bench::x86_peer(program)).c_str(), stdout);
    return 0;
  }
  bool ok = measure("blocks", blocks(1000000), 0);
  ok = measure("subroutines", subroutines(1000000), 83334) && ok;
  const std::string dense = calls(1100001);
  ok = measure("calls", dense, 91669) && ok;
  ok = versus_gnu_as("calls", dense) && ok;
  ok = measure_chain(100000) && ok;
  return ok ? 0 : 1;
}
