// Motion-core benchmark: the motion part of a program of 100,000 S-shaped moves (MVP ABS to a
// random target, then WAIT POS), driven straight through the MotionCore API as the VM drives it:
// move, ask for the next event, advance to it, check the WAIT POS condition. Goal: at least one
// million moves per second of wall time, with a cost per move independent of the move's length
// and duration (short, long and very long moves are timed separately). The same for the tmc429
// core's trapezoids, the tmc5160 core's SixPoint ramps (TMCM-1260) and the tmc5240 core's
// EightPoint ramps (TMCM-1290), and a whole program on the
// tmc429 core in the VM: a reference search on switches placed at positions, then moves for one
// simulated hour (goal: under 50 ms); and the same hour after homing by stall instead (issue 34:
// a TMCM-1110 driving into a hard stop until stop on stall, its interrupt, back off, SAP 1).
// Prints rows "figure<TAB>goal<TAB>measured".
#include <chrono>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"
#include "tmcl/vm.hpp"

namespace {

// A core on a profile with some parameters set.
struct Setup {
  const char* core;
  const char* profile;
  std::vector<std::pair<int, std::int32_t>> params;
};
const Setup kSShaped{"tmc4361", "usb-2-sd", {{14, 1}}};
const Setup kTrapezoid{"tmc4361", "usb-2-sd", {{14, 0}}};
const Setup kTmc429{"tmc429", "generic", {}};
// The TMCM-1260's SixPoint ramp: VSTART, A1 to V1, A2 to VMAX, D2 to V1, D1 to VSTOP.
const Setup kSixPoint{"tmc5160", "tmcm-1260", {{19, 1000}, {15, 100000}, {16, 20000}, {5, 50000}, {4, 60000},
                                               {17, 40000}, {18, 80000}, {20, 2000}}};
// The TMCM-1290's EightPoint ramp: VSTART, A1 to V1, A2 to V2, AMAX to VMAX, DMAX to V2, D2 to V1,
// D1 to VSTOP.
const Setup kEightPoint{"tmc5240", "tmcm-1290", {{19, 1000}, {15, 100000}, {16, 10000}, {34, 40000}, {35, 30000},
                                                 {5, 20000}, {4, 60000}, {17, 25000}, {36, 50000}, {18, 80000}, {20, 2000}}};

// Moves per second of wall time for `n` moves with targets uniform in +-range around 0.
double moves_per_second(const Setup& setup, int n, std::int32_t range, bool check) {
  auto core = tmcl::make_motion_core(setup.core);
  core->reset(*tmcl::find_profile(setup.profile), 1);
  for (auto [param, value] : setup.params) core->set_param(0, param, value);
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

// Wall milliseconds of examples/tmcm1110/stall_homing.tmc with its scenario's left hard stop at
// -20000, on the TMCM-1110 profile, its loop running until the tick timer passes one hour instead
// of two round trips: ROL into the stop until stop on stall (181) stops the motor, the stall
// interrupt (vector 15) sets user variable 0, back off 1600 microsteps, SAP 1 to 0, then MVP ABS
// 60000 / WAIT POS / MVP ABS 10000 / WAIT POS. `moves` gets the number of moves made
// (user variable 1 counts the round trips, as in the example).
double stall_homing_hour_ms(long& moves, tmcl::SimTime& simulated) {
  using tmcl::Op;
  namespace kw = tmcl::kw;
  auto core = tmcl::make_motion_core("tmc429");
  tmcl::Vm vm(*tmcl::find_profile("tmcm-1110"), *core);
  const int kStalled = 33, kWaitStall = 12, kLoop = 22;
  vm.load({I(Op::VECT, 15, 0, kStalled), I(Op::EI, 15), I(Op::EI, 255),
           I(Op::SAP, 140, 0, 4), I(Op::SAP, 154, 0, 3), I(Op::SAP, 153, 0, 7), I(Op::SAP, 4, 0, 1000),
           I(Op::SAP, 5, 0, 100), I(Op::SAP, 173, 0, 0), I(Op::SAP, 174, 0, 0), I(Op::SAP, 181, 0, 200),
           I(Op::ROL, 0, 0, 400),
           /* 12 WaitStall: */ I(Op::WAIT, kw::Wait::TICKS, 0, 10), I(Op::GGP, 0, 2), I(Op::COMP, 0, 0, 0),
           I(Op::JC, kw::Cond::EQ, 0, kWaitStall),
           I(Op::GAP, 1, 0), I(Op::CALC, kw::CalcA::ADD, 0, 1600), I(Op::AAP, 0, 0), I(Op::WAIT, kw::Wait::POS, 0, 0),
           I(Op::SAP, 1, 0, 0), I(Op::SAP, 181, 0, 0),
           /* 22 Loop: */ I(Op::MVP, kw::Move::ABS, 0, 60000), I(Op::WAIT, kw::Wait::POS, 0, 0),
           I(Op::MVP, kw::Move::ABS, 0, 10000), I(Op::WAIT, kw::Wait::POS, 0, 0),
           I(Op::GGP, 1, 2), I(Op::CALC, kw::CalcA::ADD, 0, 1), I(Op::AGP, 1, 2),  // (no CALCV on the TMCM-1110)
           I(Op::GGP, 132, 0), I(Op::COMP, 0, 0, 3600000), I(Op::JC, kw::Cond::LT, 0, kLoop), I(Op::STOP),
           /* 33 Stalled: */ I(Op::SGP, 0, 2, 1), I(Op::RETI)});
  vm.power_on(nullptr);
  tmcl::InputEvent stop;
  stop.kind = tmcl::InputEvent::HardStop;
  stop.input = tmcl::SwitchInput::StopLeft;
  stop.from = stop.to = -20000;
  vm.add_inputs({stop});
  vm.start(0);
  auto start = std::chrono::steady_clock::now();
  tmcl::RunResult r = vm.run({});
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (r.halt != tmcl::Halt::Stop) std::fprintf(stderr, "motion_bench: the stall-homing program did not stop: %s\n", r.message.c_str());
  if (vm.vars[0] != 1) std::fprintf(stderr, "motion_bench: the stall-homing program never stalled\n");
  moves = 2L * vm.vars[1];
  simulated = vm.now;
  return ms;
}

}  // namespace

int main() {
  const int n = 100000;
  moves_per_second(kSShaped, 10000, 1000000, false);  // warm up
  std::printf("S-shaped moves per second (100k MVP + WAIT POS, targets +-1e6)\t>= 1000000\t%.0f\n",
              moves_per_second(kSShaped, n, 1000000, true));
  std::printf("  short S-shaped moves per second (targets +-1000)\tsame order\t%.0f\n", moves_per_second(kSShaped, n, 1000, true));
  std::printf("  long S-shaped moves per second (targets +-2e9)\tsame order\t%.0f\n", moves_per_second(kSShaped, n, 2000000000, true));
  std::printf("  trapezoid moves per second (targets +-1e6)\tsame order\t%.0f\n", moves_per_second(kTrapezoid, n, 1000000, true));
  std::printf("tmc429 moves per second (100k MVP + WAIT POS, targets +-1e6)\t>= 1000000\t%.0f\n",
              moves_per_second(kTmc429, n, 1000000, true));
  std::printf("  short tmc429 moves per second (targets +-1000)\tsame order\t%.0f\n", moves_per_second(kTmc429, n, 1000, true));
  std::printf("tmc5160 SixPoint moves per second (100k MVP + WAIT POS, targets +-1e6)\t>= 1000000\t%.0f\n",
              moves_per_second(kSixPoint, n, 1000000, true));
  std::printf("  short tmc5160 moves per second (targets +-1000)\tsame order\t%.0f\n", moves_per_second(kSixPoint, n, 1000, true));
  std::printf("tmc5240 EightPoint moves per second (100k MVP + WAIT POS, targets +-1e6)\t>= 1000000\t%.0f\n",
              moves_per_second(kEightPoint, n, 1000000, true));
  std::printf("  short tmc5240 moves per second (targets +-1000)\tsame order\t%.0f\n", moves_per_second(kEightPoint, n, 1000, true));
  long moves = 0;
  tmcl::SimTime simulated = 0;
  homing_hour_ms(moves, simulated);  // warm up
  double ms = homing_hour_ms(moves, simulated);
  std::printf("tmc429 program: RFS, then moves for one simulated hour (%ld moves, %.0f s) (ms)\t< 50\t%.2f\n", moves,
              static_cast<double>(simulated) * 1e-6, ms);
  stall_homing_hour_ms(moves, simulated);  // warm up
  ms = stall_homing_hour_ms(moves, simulated);
  std::printf("tmc429 program (TMCM-1110): homing by stall at a hard stop, then moves for one simulated hour (%ld moves, %.0f s) (ms)\t< 50\t%.2f\n",
              moves, static_cast<double>(simulated) * 1e-6, ms);
  return 0;
}
