// Module profile benchmarks (issue 24): the cost of a profile being data, read when a tool asks
// for it. (1) tmclasm on a 500-line program with a bundled TMCM profile against the same program
// with generic, whole processes run alternately in one run, as a ratio of medians; with
// TMCL_BASELINE_TMCLASM set, also against that binary (an older tmclasm, e.g. one built from the
// commit before profiles became files). (2) Loading a user's profile file: reading the file and
// parsing it (the largest bundled profile, written out as a user's file), median of 2000 loads.
// Prints "figure<TAB>goal<TAB>measured" rows for tests/bench/run_all.sh.
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
#include "tmcl/fileio.hpp"
#include "tmcl/profile_file.hpp"

namespace {

using tmcl::bench::run_process;
using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main() {
  const std::string dir = "/tmp/tmcl-profile-bench-" + std::to_string(::getpid());
  if (std::system(("mkdir -p " + dir).c_str()) != 0) return 1;
  const std::string src = dir + "/small.tmc", out = dir + "/small.bin";
  std::ofstream(src) << tmcl::bench::tmcl_program(500, 100, "0xF");

  // (1) Whole processes, alternating so that a busy machine slows all of them alike.
  const char* baseline = std::getenv("TMCL_BASELINE_TMCLASM");
  std::vector<double> generic, tmcm, old;
  for (int i = 0; i < 300; ++i) {
    generic.push_back(run_process({TMCL_TMCLASM_PATH, "-o", out, src}));
    tmcm.push_back(run_process({TMCL_TMCLASM_PATH, "-t", "tmcm-1110", "-o", out, src}));
    if (baseline) old.push_back(run_process({baseline, "-o", out, src}));
  }
  if (*std::min_element(generic.begin(), generic.end()) < 0 || *std::min_element(tmcm.begin(), tmcm.end()) < 0) {
    std::fprintf(stderr, "profile_bench: tmclasm failed\n");
    return 1;
  }
  const double g = median(generic), t = median(tmcm);
  std::printf("tmclasm, 500 lines, -t tmcm-1110 vs generic (median of 300 runs each)\t<= 1.05x\t%.3fx (%.2f ms vs %.2f ms)\n",
              t / g, t * 1e3, g * 1e3);
  if (baseline) {
    const double b = median(old);
    std::printf("tmclasm, 500 lines, -t tmcm-1110 vs generic of %s\t<= 1.05x\t%.3fx (%.2f ms vs %.2f ms)\n", baseline, t / b, t * 1e3,
                b * 1e3);
    std::printf("tmclasm, 500 lines, generic vs generic of %s\t<= 1.05x\t%.3fx (%.2f ms vs %.2f ms)\n", baseline, g / b, g * 1e3,
                b * 1e3);
  }

  // (2) A user's profile file: read and parsed, as -t FILE does.
  const tmcl::Profile* big = tmcl::find_profile("tmcm-1110");
  if (!big) return 1;
  const std::string file = dir + "/mine.profile";
  std::ofstream(file) << big->text;
  std::vector<double> loads;
  for (int i = 0; i < 2000; ++i) {
    const auto t0 = Clock::now();
    std::vector<std::uint8_t> bytes;
    std::string error;
    std::vector<tmcl::FileDiag> diags;
    if (!tmcl::read_file(file, bytes, error)) return 1;
    auto store = tmcl::parse_profile(std::string(bytes.begin(), bytes.end()), file, file, diags);
    if (!store) return 1;
    loads.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  std::printf("loading a user's profile file (%zu lines, %zu parameters; median of 2000)\t< 0.2 ms\t%.3f ms\n",
              static_cast<std::size_t>(std::count(big->text.begin(), big->text.end(), '\n')),
              big->axis_params.size() + big->bank0.size() + big->bank3.size(), median(loads) * 1e3);
  if (std::system(("rm -rf " + dir).c_str()) != 0) return 1;
  return 0;
}
