// The `linear` motion core: the TMC2300-MOTOR-EVAL's plain linear ramp. One acceleration
// (parameter 5) for speeding up and slowing down, no start or stop velocity, speeds limited to
// ±32767 pps, in positioning and in velocity mode. Mid-move changes re-plan from the current state
// as in the tmc4361 core (same closed-form planner, ramp.hpp). The module has no stop switches,
// virtual stops or encoder: switch inputs and encoder slip do not affect it (docs/motion.md).
//
// Parameters it owns: 0-8 (6 and 7 the run and standby current, stored and reported), 140, 141,
// and 180 (the actual current: run current while moving, standby current at rest).
#include <algorithm>
#include <array>

#include "ramp_motor.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"

namespace tmcl {
namespace {

using ramp::Builder;
using ramp::EventKind;
using ramp::RampMotor;

constexpr int kLinearOwned[] = {kApTargetPosition,      kApActualPosition,         kApTargetSpeed,
                          kApActualSpeed,         kApMaxPositioningSpeed,    kApMaxAcceleration,
                          kApRunCurrent,          kApStandbyCurrent,         kApPositionReached,
                          kApMicrostepResolution, kApMicrostepInterpolation, kApSmartEnergyActualCurrent};

enum class LinearGoal : std::uint8_t { Idle, Position, Velocity };

struct LinearMotor {
  RampMotor rm;
  std::array<std::int32_t, 256> p{};
  LinearGoal goal = LinearGoal::Idle;
  std::int32_t vt = 0;
};

class LinearCore final : public ramp::RampCore<LinearMotor> {
 public:
  std::string_view name() const override { return "linear"; }
  std::unique_ptr<MotionCore> clone() const override { return std::make_unique<LinearCore>(*this); }

  LinearCore() : RampCore(kLinearOwned, "tmc2300-eval") {}  // the TMC2300-MOTOR-EVAL's ramp

  // The speed limit is the top of parameter 4's range: the active profile's, or under the generic
  // profile the TMC2300-MOTOR-EVAL's 32767 pps (core_skeleton.hpp: the profile is the only source).
  void reset(const Profile& profile, int motors) override {
    RampCore::reset(profile, motors);
    const ParamInfo* speed = range_row(kApMaxPositioningSpeed);
    vmax_ = speed ? static_cast<std::int32_t>(std::clamp<std::int64_t>(speed->max, 0, INT32_MAX)) : INT32_MAX;
  }

  void advance(SimTime to, std::vector<MotionEvent>& out) override {
    collect(to, out, [](LinearMotor& m, EventKind k) {
      if (k != EventKind::VelocityReached) m.goal = LinearGoal::Idle;
    });
  }


  ParamWrite set_param(int motor, int param, std::int32_t value) override {
    LinearMotor& m = at(motor);
    switch (param) {
      case kApTargetPosition: move_absolute(motor, value); return ParamWrite::Ok;
      case kApActualPosition:
        m.rm.shift(static_cast<std::int64_t>(value) - m.rm.xactual(now_));
        if (m.goal == LinearGoal::Position) replan(m);
        return ParamWrite::Ok;
      case kApTargetSpeed: rotate(motor, value); return ParamWrite::Ok;
      case kApActualSpeed: case kApPositionReached: case kApSmartEnergyActualCurrent: return ParamWrite::ReadOnly;
      case kApMaxPositioningSpeed: case kApMaxAcceleration: case kApRunCurrent: case kApStandbyCurrent: case kApMicrostepResolution: case kApMicrostepInterpolation:
      case kApRelativePositioningOption:  // (only under a profile that has it: core_skeleton.hpp) within the profile's range (core_skeleton.hpp)
        if (!in_range(param, value)) return ParamWrite::OutOfRange;
        break;
      default: return ParamWrite::ReadOnly;
    }
    bool changed = m.p[static_cast<std::size_t>(param)] != value;
    m.p[static_cast<std::size_t>(param)] = value;
    if (changed && (param == kApMaxPositioningSpeed || param == kApMaxAcceleration)) replan(m);
    return ParamWrite::Ok;
  }

  std::int32_t get_param(int motor, int param) override {
    LinearMotor& m = at(motor);
    switch (param) {
      case kApActualPosition: return ramp::wrap32(m.rm.xactual(now_));
      case kApTargetSpeed: return m.vt;
      case kApActualSpeed: {
        double v = m.rm.state(now_).v;
        return static_cast<std::int32_t>(v > 0 ? v + 1e-9 : v - 1e-9);
      }
      case kApPositionReached: return target_reached(motor) ? 1 : 0;
      case kApSmartEnergyActualCurrent: return m.rm.at_rest(now_) ? m.p[kApStandbyCurrent] : m.p[kApRunCurrent];
      default: return m.p[static_cast<std::size_t>(param)];
    }
  }

  void move_absolute(int motor, std::int32_t target) override {
    LinearMotor& m = at(motor);
    m.p[kApTargetPosition] = target;
    m.goal = LinearGoal::Position;
    replan(m);
  }
  void rotate(int motor, std::int32_t velocity) override {
    LinearMotor& m = at(motor);
    m.vt = std::clamp(velocity, -vmax_, vmax_);
    m.goal = LinearGoal::Velocity;
    replan(m);
  }
  void stop(int motor) override {
    LinearMotor& m = at(motor);
    if (m.goal == LinearGoal::Idle && m.rm.at_rest(now_)) return;
    m.vt = 0;
    m.goal = LinearGoal::Velocity;
    replan(m);
  }
  std::int32_t reference_search(int motor, RfsAction action) override {
    if (action != RfsAction::Start) return 0;
    zero_here(motor);
    at(motor).goal = LinearGoal::Idle;
    return 0;
  }
  void set_switch(int, SwitchInput, bool) override {}
  void encoder_slip(int, std::int32_t) override {}

 private:
  std::int32_t vmax_ = INT32_MAX;  // pps, the top of parameter 4's range (reset)

  void replan(LinearMotor& m) {
    if (m.goal == LinearGoal::Idle) return;
    ramp::Limits lim;
    lim.vmax = std::min(m.p[kApMaxPositioningSpeed], vmax_);
    lim.amax = lim.astart = lim.dmax = lim.dfinal = m.p[kApMaxAcceleration];
    Builder b = m.rm.restart(now_);
    if (m.goal == LinearGoal::Position)
      b.plan_position(lim, static_cast<double>(m.p[kApTargetPosition] - m.rm.base));
    else
      b.plan_velocity(lim, m.vt);
  }
};

}  // namespace

std::unique_ptr<MotionCore> make_linear_motion_core() { return std::make_unique<LinearCore>(); }

}  // namespace tmcl
