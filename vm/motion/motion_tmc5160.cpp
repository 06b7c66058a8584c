// The `tmc5160` motion core: the ramp generator of the TMCM-1260 (PD57-1260, PD60-1260), a
// TMC5160, as the module's firmware manual 1.44 describes it: speeds in pps, accelerations in
// pps². Positioning (MVP) runs the SixPoint ramp (sections 1.3 and 7.5): from VSTART (19) with A1
// (15) up to V1 (16), with A2 (5) up to VMAX (4); down with D2 (17) to V1, with D1 (18) to VSTOP
// (20); V1 = 0 leaves A2 and D2 alone. Velocity mode (ROR, ROL, MST) ramps with A2 both ways,
// from and to standstill. The limit switches with their stop functions (12, 13: disable; 26: soft
// stop) and the reference search (RFS, 193-197, with +64 for the other end switch) are the shared
// part of switch_core.hpp; the home switch has its own input. docs/motion.md explains every
// decision, docs/errata.md where the manual is silent.
//
// Parameters it owns: 0-13, 15-20, 26, 127, 140, 168-174, 180-182, 193-197, 206, 208, and 207, 209,
// 210, 212 (the SensOstep encoder, switch_core.hpp).
#include <algorithm>
#include <cstdint>
#include <limits>

#include "switch_core.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"

namespace tmcl {
namespace {

// The TMCM-1260's numbers beyond the shared ones (PD57/60-1260 manual, chapter 4).
enum Tmc5160Param : int {
  kA1 = 15,
  kV1 = 16,
  kD2 = 17,                // "maximum deceleration"
  kD1 = 18,
  kVStart = 19,
  kVStop = 20,
  kLimitSoftStop = 26,     // 1: a limit switch stops with the ramp, 0: at once
  kRelativeOption = 127,   // MVP REL from 0: the last target, 1: the actual position
  kLastReference = 197,
};

constexpr int kTmc5160Owned[] = {kApTargetPosition, kApActualPosition, kApTargetSpeed, kApActualSpeed,
                                 kApMaxPositioningSpeed, kApMaxAcceleration, kApPositionReached,
                                 sw::kHomeState, sw::kRightSwitchState, sw::kLeftSwitchState,
                                 sw::kRightStopDisable, sw::kLeftStopDisable, kA1, kV1, kD2, kD1, kVStart,
                                 kVStop, kLimitSoftStop, kRelativeOption, sw::kRfsMode, sw::kRfsSpeed,
                                 sw::kRfsSwitchSpeed, sw::kRfsDistance, kLastReference,
                                 sw::kErrorFlags, sw::kEncoderPosition, sw::kEncoderPrescaler, sw::kMaxDeviation,
                                 // stallGuard2 (stall_core.cpp): run current, microsteps, filter, threshold, stop on stall, load value, driver flags
                                 6, 140, 173, 174, 181, 206, 208,
                                 // StealthChop, in which stallGuard2 measures nothing: PWM threshold speed, PWM gradient
                                 186, 187,
                                // coolStep (coolstep_core.cpp): standby current, 168-172, actual current, threshold speed
                                7, 168, 169, 170, 171, 172, 180, 182};

class Tmc5160Core final : public sw::SwitchCore {
 public:
  std::string_view name() const override { return "tmc5160"; }
  std::unique_ptr<MotionCore> clone() const override { return std::make_unique<Tmc5160Core>(*this); }

  // Its parameters are in pps like the generic profile's, but numbered as the TMCM-1260 numbers
  // them: under generic its rows come from the TMCM-1260's profile.
  Tmc5160Core() : SwitchCore(kTmc5160Owned, "tmcm-1260", true, {kLimitSoftStop, false, true, kLastReference}) {}

  // A SixPoint ramp that cannot leave VSTART or reach VSTOP leaves MVP standing; VSTART above
  // VSTOP the manual forbids ("do not set VSTART higher than VSTOP", parameter 19).
  std::string move_problem(int motor) const override {
    const sw::Motor& m = motors_[static_cast<std::size_t>(motor)];
    if (m.goal != sw::Goal::Position) return {};
    auto v = [&](int n) { return std::to_string(m.p[static_cast<std::size_t>(n)]); };
    const bool standing = !target_reached(motor) && m.rm.at_rest(now_);
    if (standing && m.p[kV1] > 0 && m.p[kA1] == 0)
      return "the move cannot start: A1 (axis parameter 15) is 0 while V1 (16) is " + v(kV1) + " (set A1, or V1 = 0 for A2 alone)";
    if (standing && m.p[kV1] > 0 && m.p[kD1] == 0)
      return "the move cannot start: D1 (axis parameter 18) is 0 while V1 (16) is " + v(kV1) + " (set D1, or V1 = 0 for D2 alone)";
    if (standing && m.p[kApMaxAcceleration] == 0) return "the move cannot start: A2 (axis parameter 5) is 0";
    if (standing && m.p[kD2] == 0) return "the move cannot start: D2 (axis parameter 17) is 0";
    if (standing && m.p[kApMaxPositioningSpeed] == 0) return "the move cannot start: VMAX (axis parameter 4) is 0";
    if (m.p[kVStart] > m.p[kVStop])
      return "VSTART (axis parameter 19) is " + v(kVStart) + ", above VSTOP (20) " + v(kVStop) +
             ": the manual says not to set VSTART higher than VSTOP";
    return {};
  }

 protected:
  double vunit(const sw::Motor&) const override { return 1; }  // pps
  // The velocity register's bound: the range of parameter 2 in the profile.
  std::int32_t max_speed() const override {
    const ParamInfo* row = range_row(kApTargetSpeed);
    return row ? static_cast<std::int32_t>(std::min<std::int64_t>(row->max, std::numeric_limits<std::int32_t>::max()))
               : std::numeric_limits<std::int32_t>::max();
  }
  ramp::Limits ramp_limits(const sw::Motor& m) const override {
    if (m.goal == sw::Goal::Position) return sixpoint(m, m.p[kApMaxPositioningSpeed]);
    return velocity(m, max_speed());
  }
  ramp::Limits search_limits(const sw::Motor& m, std::int32_t speed, bool positioning) const override {
    return positioning ? sixpoint(m, speed) : velocity(m, speed);
  }

 private:
  static double p(const sw::Motor& m, int n) { return std::max(0, m.p[static_cast<std::size_t>(n)]); }
  // The SixPoint ramp with top speed `vmax` (pps); V1 = 0: A2 and D2 alone (manual, parameter 16).
  static ramp::Limits sixpoint(const sw::Motor& m, std::int32_t vmax) {
    ramp::Limits l;
    l.vmax = std::max(0, vmax);
    l.amax = p(m, kApMaxAcceleration);
    l.dmax = p(m, kD2);
    l.vbreak = p(m, kV1);
    l.astart = l.vbreak > 0 ? p(m, kA1) : l.amax;
    l.dfinal = l.vbreak > 0 ? p(m, kD1) : l.dmax;
    l.vstart = std::min(p(m, kVStart), l.vmax);
    l.vstop = p(m, kVStop);
    return l;
  }
  // Velocity mode: A2 both ways, from and to standstill (manual 7.5; docs/errata.md).
  static ramp::Limits velocity(const sw::Motor& m, std::int32_t vmax) {
    ramp::Limits l;
    l.vmax = std::max(0, vmax);
    l.amax = l.astart = l.dmax = l.dfinal = p(m, kApMaxAcceleration);
    return l;
  }
};

}  // namespace

std::unique_ptr<MotionCore> make_tmc5160_motion_core() { return std::make_unique<Tmc5160Core>(); }

}  // namespace tmcl
