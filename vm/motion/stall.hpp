// StallGuard2's load value as the TMCM modules' cores model it (docs/motion.md, "Loads, stalls and
// lost steps"): the formulas, and the machine a motor drives (hard stops, loads) with what the
// driver last measured. The TMCM-1110 manual (5.1) and the PD57/60-1260 manual (7.2) say only
// that the value "changes linear with the load ... in a wide range of load, velocity and current
// settings", that "at maximum motor load the value goes to zero", that 174 shifts it ("a higher
// value makes stallGuard2 less sensitive and requires more torque to indicate a stall"), and that
// it is measured once per fullstep, once per four with the filter (173). The numbers below are
// this model's, not a motor's (docs/errata.md E61): the simulation reproduces the events, their
// order and their instants, not a particular motor's readings.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tmcl/sim_time.hpp"

namespace tmcl::stall {

inline constexpr double kMinFullstepRate = 20;  // fullsteps/s: below it nothing is measured (E61)
inline constexpr double kThresholdGain = 8;     // reading units per unit of 174 (E61)
inline constexpr int kMaxReading = 1023;

// The reading without load at `f` fullsteps/s and current scale cs (0..31, 32 steps of the run
// current 6): 250 + 500 · (cs + 1)/32 · f / (f + 500). It rises with the speed (the back EMF the
// driver measures) and with the current, from 250 toward 750.
inline double no_load(double f, int cs) { return 250 + 500 * (cs + 1) / 32.0 * f / (f + 500); }

// The load value at `f` fullsteps/s, current scale cs, load `percent` % of the holding torque and
// threshold sgt (174): the no-load value falling linearly to 0 at 100 %, shifted by 8 · sgt,
// rounded and held within 0..1023.
inline int reading(double f, int cs, int percent, int sgt) {
  const double free = std::max(0.0, 1.0 - percent / 100.0);
  const double r = std::round(no_load(f, cs) * free + kThresholdGain * sgt);
  return static_cast<int>(std::clamp(r, 0.0, static_cast<double>(kMaxReading)));
}

// The fullstep rate below which no_load(f, cs) · (1 - percent/100) < need under that load (it
// rises with f): 0 when it never is, infinity when it always is.
inline double below(int cs, int percent, double need) {
  const double free = std::max(0.0, 1.0 - percent / 100.0);
  if (free <= 0) return need > 0 ? INFINITY : 0;
  const double k = need / free;  // no_load(f) < k
  const double a = 500 * (cs + 1) / 32.0, r = (k - 250) / a;  // f / (f + 500) < r
  if (r <= 0) return 0;
  if (r >= 1) return INFINITY;
  return 500 * r / (1 - r);
}
// The fullstep rate below which the stallGuard2 reading is 0.
inline double zero_below(int cs, int percent, int sgt) { return below(cs, percent, 0.5 - kThresholdGain * sgt); }

// ---- the other drivers' load measurements (docs/errata.md E74, E75)
// Which measurement the module's driver makes: the profile's `motion-constant stallguard N`
// (1, 2 or 4), 2 where the profile lists only stallGuard2's threshold 174 (the TMCM modules).
enum class Guard : std::uint8_t { None = 0, SG1 = 1, SG2 = 2, SG4 = 4 };

// StallGuard4 (TMC2300): the same no-load curve, no shift by the threshold: SGTHRS (174) is the
// level the reading is compared with, a stall when reading <= 2 · SGTHRS (E74).
inline int reading4(double f, int cs, int percent) { return reading(f, cs, percent, 0); }
inline int stall_level4(int sgthrs) { return 2 * std::max(0, sgthrs); }
// The fullstep rate below which the StallGuard4 reading is at or under 2 · sgthrs.
inline double stall_below4(int cs, int percent, int sgthrs) { return below(cs, percent, stall_level4(sgthrs) + 0.5); }

// stallGuard 1 (TMC249, TMCM-351): a load indicator 0..7 rising with the load, 7 at 100 % and
// above; the motor stops when it reaches the threshold 205 (1..7; E75).
inline constexpr int kMaxReading1 = 7;
inline int reading1(int percent) {
  return static_cast<int>(std::lround(kMaxReading1 * std::clamp(percent, 0, 100) / 100.0));
}

// A load while the shaft is in [lo, hi] (scenario `load M from A to B = P%`).
struct LoadZone {
  std::int64_t lo, hi;
  int percent;
};

// One motor's machine and driver state.
struct Axis {
  int load = 0;                    // the timed load, %
  std::vector<LoadZone> zones;     // loads at positions, in the machine's frame
  bool hard[2] = {false, false};   // hard stop left (0) / right (1) placed
  std::int64_t hard_at[2] = {0, 0};
  int block = 0;                   // the shaft is held: -1 pushing left, +1 pushing right, 2 by a load
  bool measured = false;           // a measurement was made since power-on
  int value = 0;                   // 206: the last measurement
  SimTime commit_us = 0;           // the instant up to which `value` is brought
  std::int32_t flags208 = 0;       // bit 0: stallGuard2 status (the last measurement read 0)
  bool lost_said = false;          // "steps lost" reported for the current block
  // The next mechanical event under the current plan and inputs (cached).
  mutable bool next_valid = false;
  mutable SimTime next_at = kNever;
  mutable int next_kind = 0;       // 1 stall, 2 contact (hold), 3 release
  mutable std::uint32_t next_gen = 0;

  bool has_machine() const { return hard[0] || hard[1] || !zones.empty() || load > 0; }
};

}  // namespace tmcl::stall
