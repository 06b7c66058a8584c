// The `linear` motion core: the TMC2300-MOTOR-EVAL's plain linear ramp. One acceleration
// (parameter 5) for speeding up and slowing down, no start or stop velocity, speeds limited to
// ±32767 pps, in positioning and in velocity mode. Mid-move changes re-plan from the current state
// (same closed-form planner, ramp.hpp). The module has no stop switches, no reference search and
// no encoder: switches placed by a scenario only report their edges, RFS makes the place where the
// motor stands position 0, timed switch inputs and encoder slip do not affect it (docs/motion.md).
// It is built on the TMCM cores' shared part (switch_core.hpp) for the machine and the load model:
// hard stops and loads hold the shaft, and the TMC2300's StallGuard4 (the profile's
// `motion-constant stallguard 4`, stall_core.cpp; errata E74) gives 206 and stop on stall (181).
//
// Parameters it owns: 0-8 (6 and 7 the run and standby current, stored and reported), 140, 141,
// 174, 181, 187 (StallGuard4 works in StealthChop only), 206, and coolStep's 168-172, 182 and 180
// (the actual current: the standby current at rest, the run current while moving, and the scale
// coolStep regulates on StallGuard4's readings, coolstep_core.cpp; errata E73).
#include <algorithm>
#include <cstdint>

#include "switch_core.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"

namespace tmcl {
namespace {

constexpr int kSgThreshold = 174, kStopOnStall = 181, kPwmGradient = 187, kLoadValue = 206;
constexpr int kCsSeimin = 168, kCsSedn = 169, kCsSemax = 170, kCsSeup = 171, kCsSemin = 172, kCsThresholdSpeed = 182;

constexpr int kLinearOwned[] = {kApTargetPosition,      kApActualPosition,         kApTargetSpeed,
                                kApActualSpeed,         kApMaxPositioningSpeed,    kApMaxAcceleration,
                                kApRunCurrent,          kApStandbyCurrent,         kApPositionReached,
                                kApMicrostepResolution, kApMicrostepInterpolation, kApSmartEnergyActualCurrent,
                                // StallGuard4 (stall_core.cpp)
                                kSgThreshold, kStopOnStall, kPwmGradient, kLoadValue,
                                // coolStep on StallGuard4 (coolstep_core.cpp)
                                kCsSeimin, kCsSedn, kCsSemax, kCsSeup, kCsSemin, kCsThresholdSpeed};

class LinearCore final : public sw::SwitchCore {
 public:
  std::string_view name() const override { return "linear"; }
  std::unique_ptr<MotionCore> clone() const override { return std::make_unique<LinearCore>(*this); }

  // The TMC2300-MOTOR-EVAL's ramp: no limit-switch stop function, no reference search.
  LinearCore() : SwitchCore(kLinearOwned, "tmc2300-eval", false, {0, false, false, 0, false}) {}

  // The speed limit is the top of parameter 4's range: the active profile's, or under the generic
  // profile the TMC2300-MOTOR-EVAL's 32767 pps (core_skeleton.hpp: the profile is the only source).
  void reset(const Profile& profile, int motors) override {
    SwitchCore::reset(profile, motors);
    const ParamInfo* speed = range_row(kApMaxPositioningSpeed);
    vmax_ = speed ? static_cast<std::int32_t>(std::clamp<std::int64_t>(speed->max, 0, INT32_MAX)) : INT32_MAX;
  }

  ParamWrite set_param(int motor, int param, std::int32_t value) override {
    if (param == kApSmartEnergyActualCurrent) return ParamWrite::ReadOnly;
    return SwitchCore::set_param(motor, param, value);
  }

  // 180 without coolStep (a profile of this core that lists no 172): the run or standby current.
  std::int32_t get_param(int motor, int param) override {
    if (param == kApSmartEnergyActualCurrent && !has_coolstep()) {
      const sw::Motor& m = at(motor);
      return m.rm.at_rest(now_) ? m.p[kApStandbyCurrent] : m.p[kApRunCurrent];
    }
    return SwitchCore::get_param(motor, param);
  }
  std::optional<std::int32_t> sample_param(int motor, int param, SimTime t) const override {
    if (param == kApSmartEnergyActualCurrent && !has_coolstep()) {
      const sw::Motor& m = motors_[static_cast<std::size_t>(motor)];
      return m.rm.at_rest(t) ? m.p[kApStandbyCurrent] : m.p[kApRunCurrent];
    }
    return SwitchCore::sample_param(motor, param, t);
  }

  std::int32_t reference_search(int motor, RfsAction action) override {
    if (action != RfsAction::Start) return 0;
    zero_here(motor);
    set_goal(at(motor), sw::Goal::Idle);
    return 0;
  }
  void set_switch(int, SwitchInput, bool) override {}
  void encoder_slip(int, std::int32_t) override {}
  bool models_encoder(const Profile&) const override { return false; }

 protected:
  double vunit(const sw::Motor&) const override { return 1; }  // pps
  std::int32_t max_speed() const override { return vmax_; }
  ramp::Limits ramp_limits(const sw::Motor& m) const override {
    ramp::Limits lim;
    lim.vmax = std::min(m.p[kApMaxPositioningSpeed], vmax_);
    lim.amax = lim.astart = lim.dmax = lim.dfinal = m.p[kApMaxAcceleration];
    return lim;
  }
  ramp::Limits search_limits(const sw::Motor& m, std::int32_t, bool) const override { return ramp_limits(m); }
  // Parameter 2 reads the last velocity commanded (the module's step generator keeps it).
  std::int32_t target_speed(const sw::Motor& m, const ramp::State&) const override { return m.vt; }
  // Only the ramp's speed and acceleration re-plan a move; the other settings are stored.
  ParamWrite set_other(sw::Motor& m, int param, std::int32_t value) override {
    if (param == kApMaxPositioningSpeed || param == kApMaxAcceleration) return SwitchCore::set_other(m, param, value);
    if (!in_range(param, value)) return ParamWrite::OutOfRange;
    m.p[static_cast<std::size_t>(param)] = value;
    return ParamWrite::Ok;
  }

 private:
  std::int32_t vmax_ = INT32_MAX;  // pps, the top of parameter 4's range (reset)
};

}  // namespace

std::unique_ptr<MotionCore> make_linear_motion_core() { return std::make_unique<LinearCore>(); }

}  // namespace tmcl
