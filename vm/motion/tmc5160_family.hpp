// The ramp generators of the TMC5160 and TMC5240 as the TMCM modules expose them in pps and
// pps² (the `tmc5160` core: TMCM-1260; the `tmc5240` core: TMCM-1290, TMCM-3216): one class, the
// parameter numbers and names per chip. Positioning (MVP) runs the SixPoint ramp (VSTART, A1 to
// V1, AMAX to VMAX; DMAX down to V1, D1 to VSTOP), which the TMC5240's EightPoint ramp extends by
// one band: A2 from V1 to V2, D2 from V2 to V1 (ramp::Limits' middle band). A phase whose speed
// is 0 is skipped (V1 = 0: AMAX and DMAX alone; V2 = 0: no A2/D2). Velocity mode (ROR, ROL, MST) ramps with
// AMAX both ways, from and to standstill. The limit switches, the reference search, the
// encoder, stallGuard2 and coolStep are the shared part (switch_core.hpp). docs/motion.md
// explains every decision.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>

#include "switch_core.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"

namespace tmcl::sw {

// The numbers both modules' manuals give the family's ramp (PD57/60-1260 chapter 4, TMCM-1290
// table 16); 17, the deceleration down to V1, is each core's own name (D2 on the TMCM-1260,
// DMAX on the TMCM-1290).
enum Tmc5160FamilyParam : int {
  kA1 = 15,
  kV1 = 16,
  kD1 = 18,
  kVStart = 19,
  kVStop = 20,
  kLimitSoftStop = 26,     // 1: a limit switch (and a virtual stop) stops with the ramp, 0: at once
  kRelativeOption = 127,   // MVP REL from 0: the last target, 1: the actual position
  kLastReference = 197,
};

// A chip's ramp parameters: their numbers, and the names the module's manual gives AMAX and DMAX
// (the TMCM-1260 calls them A2 and D2). a2/v2/d2 = 0: no middle band (SixPoint);
// zero_wait = 0: the ramp wait time is not modelled.
struct RampNumbers {
  int a1, v1, dmax, d1, vstart, vstop;
  const char* amax_name;
  const char* dmax_name;
  int a2 = 0, v2 = 0, d2 = 0;
  int zero_wait = 0;           // 32 µs per unit (TZEROWAIT)
};

class Tmc5160Family : public SwitchCore {
 public:
  Tmc5160Family(std::span<const int> owned, std::string_view home, SwitchConfig cfg, RampNumbers n)
      : SwitchCore(owned, home, true, cfg), n_(n) {}

  // A ramp that cannot leave VSTART or reach VSTOP leaves MVP standing; VSTART above VSTOP the
  // manuals forbid ("do not set VSTART higher than VSTOP", parameter 19).
  std::string move_problem(int motor) const override {
    const Motor& m = motors_[static_cast<std::size_t>(motor)];
    if (m.goal != Goal::Position) return {};
    auto v = [&](int k) { return std::to_string(m.p[static_cast<std::size_t>(k)]); };
    auto num = [](int k) { return std::to_string(k); };
    const bool standing = !target_reached(motor) && m.rm.at_rest(now_);
    if (standing && m.p[n_.v1] > 0 && m.p[n_.a1] == 0)
      return "the move cannot start: A1 (axis parameter " + num(n_.a1) + ") is 0 while V1 (" + num(n_.v1) + ") is " + v(n_.v1) +
             " (set A1, or V1 = 0 for " + n_.amax_name + " alone)";
    if (standing && m.p[n_.v1] > 0 && m.p[n_.d1] == 0)
      return "the move cannot start: D1 (axis parameter " + num(n_.d1) + ") is 0 while V1 (" + num(n_.v1) + ") is " + v(n_.v1) +
             " (set D1, or V1 = 0 for " + n_.dmax_name + " alone)";
    if (standing && mid_band(m) && m.p[n_.a2] == 0)
      return "the move cannot start: A2 (axis parameter " + num(n_.a2) + ") is 0 while V2 (" + num(n_.v2) + ") is " + v(n_.v2) +
             " (set A2, or V2 = 0 for " + n_.amax_name + " alone)";
    if (standing && mid_band(m) && m.p[n_.d2] == 0)
      return "the move cannot start: D2 (axis parameter " + num(n_.d2) + ") is 0 while V2 (" + num(n_.v2) + ") is " + v(n_.v2) +
             " (set D2, or V2 = 0 for " + n_.dmax_name + " alone)";
    if (standing && m.p[kApMaxAcceleration] == 0) return std::string("the move cannot start: ") + n_.amax_name + " (axis parameter 5) is 0";
    if (standing && m.p[n_.dmax] == 0)
      return std::string("the move cannot start: ") + n_.dmax_name + " (axis parameter " + num(n_.dmax) + ") is 0";
    if (standing && m.p[kApMaxPositioningSpeed] == 0) return "the move cannot start: VMAX (axis parameter 4) is 0";
    if (m.p[n_.vstart] > m.p[n_.vstop])
      return "VSTART (axis parameter " + num(n_.vstart) + ") is " + v(n_.vstart) + ", above VSTOP (" + num(n_.vstop) + ") " +
             v(n_.vstop) + ": the manual says not to set VSTART higher than VSTOP";
    return {};
  }

 protected:
  double vunit(const Motor&) const override { return 1; }  // pps
  // The velocity register's bound: the range of parameter 2 in the profile.
  std::int32_t max_speed() const override {
    const ParamInfo* row = range_row(kApTargetSpeed);
    return row ? static_cast<std::int32_t>(std::min<std::int64_t>(row->max, std::numeric_limits<std::int32_t>::max()))
               : std::numeric_limits<std::int32_t>::max();
  }
  ramp::Limits ramp_limits(const Motor& m) const override {
    if (m.goal == Goal::Position) return positioning(m, m.p[kApMaxPositioningSpeed]);
    return velocity(m, max_speed());
  }
  ramp::Limits search_limits(const Motor& m, std::int32_t speed, bool positioning_step) const override {
    return positioning_step ? positioning(m, speed) : velocity(m, speed);
  }

  static double p(const Motor& m, int k) { return k > 0 ? std::max(0, m.p[static_cast<std::size_t>(k)]) : 0; }
  // The A2/D2 band: V1 = 0 is the plain trapezoid of AMAX and DMAX (TMCM-1290 manual 7.6: it
  // "switches off the EightPoint ramp"); V2 at or below V1 leaves the band empty (skipped).
  bool mid_band(const Motor& m) const { return n_.v2 > 0 && p(m, n_.v1) > 0 && p(m, n_.v2) > p(m, n_.v1); }
  double zero_wait(const Motor& m) const { return p(m, n_.zero_wait) * 32e-6; }

  // The positioning ramp with top speed `vmax` (pps).
  ramp::Limits positioning(const Motor& m, std::int32_t vmax) const {
    ramp::Limits l;
    l.vmax = std::max(0, vmax);
    l.amax = p(m, kApMaxAcceleration);
    l.dmax = p(m, n_.dmax);
    l.vbreak = p(m, n_.v1);
    l.astart = l.vbreak > 0 ? p(m, n_.a1) : l.amax;
    l.dfinal = l.vbreak > 0 ? p(m, n_.d1) : l.dmax;
    if (mid_band(m)) {
      l.vbreak2 = p(m, n_.v2);
      l.amid = p(m, n_.a2);
      l.dmid = p(m, n_.d2);
    }
    l.vstart = std::min(p(m, n_.vstart), l.vmax);
    l.vstop = p(m, n_.vstop);
    l.zero_wait = zero_wait(m);
    return l;
  }
  // Velocity mode: AMAX both ways, from and to standstill (manuals 7.5; docs/errata.md).
  ramp::Limits velocity(const Motor& m, std::int32_t vmax) const {
    ramp::Limits l;
    l.vmax = std::max(0, vmax);
    l.amax = l.astart = l.dmax = l.dfinal = p(m, kApMaxAcceleration);
    l.zero_wait = zero_wait(m);
    return l;
  }

  RampNumbers n_;
};

}  // namespace tmcl::sw
