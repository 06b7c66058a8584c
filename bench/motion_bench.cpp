// Motion-core benchmark: the motion part of a program of 100,000 S-shaped moves (MVP ABS to a
// random target, then WAIT POS), driven straight through the MotionCore API as the VM drives it:
// move, ask for the next event, advance to it, check the WAIT POS condition. Goal: at least one
// million moves per second of wall time, with a cost per move independent of the move's length
// and duration (short, long and very long moves are timed separately).
// Prints rows "figure<TAB>goal<TAB>measured".
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"

namespace {

// Moves per second of wall time for `n` moves with targets uniform in +-range around 0.
double moves_per_second(int n, std::int32_t range, int ramp_type, bool check) {
  auto core = tmcl::make_motion_core("tmc4361");
  core->reset(*tmcl::find_profile("usb-2-sd"), 1);
  core->set_param(0, 14, ramp_type);
  std::mt19937 rng(2024);
  std::uniform_int_distribution<std::int32_t> pick(-range, range);
  std::vector<std::int32_t> targets(static_cast<std::size_t>(n));
  for (auto& t : targets) t = pick(rng);
  std::vector<tmcl::MotionEvent> events;
  events.reserve(16);
  long bad = 0;
  auto start = std::chrono::steady_clock::now();
  for (std::int32_t target : targets) {
    core->move_absolute(0, target);              // MVP ABS, 0, target
    tmcl::SimTime t = core->next_event();        // the VM sleeps until then
    events.clear();
    core->advance(t, events);
    if (!core->target_reached(0)) ++bad;          // WAIT POS ends
    if (check && core->position(0) != target) ++bad;
  }
  double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (bad) std::fprintf(stderr, "motion_bench: %ld moves did not end on their target\n", bad);
  return n / s;
}

}  // namespace

int main() {
  const int n = 100000;
  moves_per_second(10000, 1000000, 1, false);  // warm up
  std::printf("S-shaped moves per second (100k MVP + WAIT POS, targets +-1e6)\t>= 1000000\t%.0f\n",
              moves_per_second(n, 1000000, 1, true));
  std::printf("  short S-shaped moves per second (targets +-1000)\tsame order\t%.0f\n", moves_per_second(n, 1000, 1, true));
  std::printf("  long S-shaped moves per second (targets +-2e9)\tsame order\t%.0f\n", moves_per_second(n, 2000000000, 1, true));
  std::printf("  trapezoid moves per second (targets +-1e6)\tsame order\t%.0f\n", moves_per_second(n, 1000000, 0, true));
  return 0;
}
