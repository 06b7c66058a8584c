// Motion-core benchmark: the motion part of a program of 100,000 S-shaped moves (MVP ABS to a
// random target, then WAIT POS), driven straight through the MotionCore API as the VM drives it:
// move, ask for the next event, advance to it, check the WAIT POS condition. Goal: at least one
// million moves per second of wall time, with a cost per move independent of the move's length
// and duration (short, long and very long moves are timed separately). The same for the tmc429
// core's trapezoids, and a whole program on it in the VM: a reference search on switches placed
// at positions, then moves for one simulated hour (goal: under 50 ms).
// Prints rows "figure<TAB>goal<TAB>measured".
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"
#include "tmcl/vm.hpp"

namespace {

// Moves per second of wall time for `n` moves with targets uniform in +-range around 0.
// ramp_type < 0: the tmc429 core (TMC429 units, trapezoids), else the tmc4361's parameter 14.
double moves_per_second(int n, std::int32_t range, int ramp_type, bool check) {
  auto core = tmcl::make_motion_core(ramp_type < 0 ? "tmc429" : "tmc4361");
  core->reset(*tmcl::find_profile(ramp_type < 0 ? "generic" : "usb-2-sd"), 1);
  if (ramp_type >= 0) core->set_param(0, 14, ramp_type);
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

tmcl::Instruction I(tmcl::Op op, int type = 0, int motor = 0, std::int32_t value = 0) {
  return tmcl::Instruction{static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor),
                           value};
}

// Wall milliseconds of a TMCM-1110-style program on the tmc429 core: RFS on the left stop switch
// (placed at -20000), then MVP ABS 100000 / WAIT POS / MVP ABS 0 / WAIT POS until the tick timer
// passes one hour. `moves` gets the number of moves made.
double homing_hour_ms(long& moves, tmcl::SimTime& simulated) {
  using tmcl::Op;
  auto core = tmcl::make_motion_core("tmc429");
  tmcl::Vm vm(tmcl::generic_profile(), *core);
  vm.load({I(Op::SAP, 5, 0, 100), I(Op::SAP, 193, 0, 1), I(Op::RFS, 0, 0), I(Op::WAIT, 4, 0, 0),
           I(Op::MVP, 0, 0, 100000), I(Op::WAIT, 1, 0, 0), I(Op::CALCV, 0, 1, 2), I(Op::MVP, 0, 0, 0), I(Op::WAIT, 1, 0, 0),
           I(Op::GGP, 132, 0), I(Op::COMP, 0, 0, 3600000), I(Op::JC, 6, 0, 4), I(Op::STOP)});
  vm.power_on(nullptr);
  tmcl::InputEvent left;
  left.kind = tmcl::InputEvent::Placed;
  left.input = tmcl::SwitchInput::StopLeft;
  left.from = INT64_MIN;
  left.to = -20000;
  vm.add_inputs({left});
  vm.start(0);
  auto start = std::chrono::steady_clock::now();
  tmcl::RunResult r = vm.run({});
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (r.halt != tmcl::Halt::Stop) std::fprintf(stderr, "motion_bench: the homing program did not stop: %s\n", r.message.c_str());
  moves = vm.vars[1];
  simulated = vm.now;
  return ms;
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
  std::printf("tmc429 moves per second (100k MVP + WAIT POS, targets +-1e6)\t>= 1000000\t%.0f\n",
              moves_per_second(n, 1000000, -1, true));
  std::printf("  short tmc429 moves per second (targets +-1000)\tsame order\t%.0f\n", moves_per_second(n, 1000, -1, true));
  long moves = 0;
  tmcl::SimTime simulated = 0;
  homing_hour_ms(moves, simulated);  // warm up
  double ms = homing_hour_ms(moves, simulated);
  std::printf("tmc429 program: RFS, then moves for one simulated hour (%ld moves, %.0f s) (ms)\t< 50\t%.2f\n", moves,
              static_cast<double>(simulated) * 1e-6, ms);
  return 0;
}
