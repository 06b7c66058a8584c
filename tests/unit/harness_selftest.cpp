// Cases for the harness's own test (harness_selftest.cmake): one slow that passes, one that
// fails a check, one whose process dies. Run only by that script, with --jobs: the case that
// dies would end a serial run.
#include <csignal>
#include <thread>

#include "check.hpp"

TEST(slow_pass) {
  // Slower than the two after it, so with --jobs their outputs are ready first and must wait.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  std::fprintf(stderr, "output of slow_pass\n");
  CHECK_EQ(1 + 1, 2);
}

TEST(fails_a_check) {
  std::fprintf(stderr, "output of fails_a_check\n");
  CHECK_EQ(1 + 1, 3);
}

TEST(dies) {
  std::fprintf(stderr, "output of dies\n");
  std::fflush(stderr);
  std::raise(SIGKILL);
}
