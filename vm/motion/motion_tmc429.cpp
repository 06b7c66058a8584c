// The `tmc429` motion core: the ramp generator of the TMCM-1110, -3110, -6110 and -351 (a TMC429)
// as their firmware manuals describe it. Speeds and accelerations are the chip's whole units,
// scaled by the pulse divisor (154) and the ramp divisor (153):
//   microstep rate  = fCLK * v / 2^(pulse_div + 16)            (2048 * 32 = 2^16)
//   acceleration    = fCLK^2 * a_max / 2^(pulse_div + ramp_div + 29)
// with fCLK = 16 MHz (TMCM-1110 manual, section 5.5). Trapezoid ramps with one acceleration both
// ways and the minimum speed (130) as start and stop speed, velocity mode, re-targeting from the
// current state (the closed-form planner of ramp.hpp), the soft positioning mode (138 = 1). The
// limit switches with their stop functions (12, 13: disable; 149: soft stop) and the modules'
// reference search (RFS, 193-197) are the shared part of switch_core.hpp; the TMC429 modules wire
// the home switch in series with the left one (mode 3 searches either). docs/motion.md explains
// every decision.
//
// Parameters it owns: 0-13, 130, 135, 138, 140, 149, 153, 154, 168-174, 180-182, 193-197, 205, 206,
// 208, and 207, 209, 210, 212 (the encoder where the profile declares one, switch_core.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "switch_core.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"

namespace tmcl {
namespace {

using ramp::Builder;
using ramp::Limits;
using sw::Goal;

constexpr int kChipMax = 2047;         // velocity and acceleration registers: 11 bits

// The parameters of the TMC429 modules this core gives a meaning beyond the shared ones
// (TMCM-1110 manual, chapter 5).
enum Tmc429Param : int {
  kMinSpeed = 130,
  kActualAcceleration = 135,
  kRampMode = 138,         // 0 position, 1 soft, 2 velocity
  kSoftStop = 149,         // 1: a stop switch stops with the ramp, 0: at once
  kRampDivisor = 153,
  kPulseDivisor = 154,
  // "the last position value before the position counter is set to zero during reference search"
  // (PD57/60-1260 manual, 197; TMCM-351 firmware 4.41's release note): the TMCM-1140, -1160,
  // -1161, -3110, -6110 and -351 list it (the TMCM-1110's manual does not; errata M31).
  kLastReferencePosition = 197,
};

constexpr int kTmc429Owned[] = {kApTargetPosition, kApActualPosition, kApTargetSpeed, kApActualSpeed,
                                kApMaxPositioningSpeed, kApMaxAcceleration, kApPositionReached,
                                sw::kHomeState, sw::kRightSwitchState, sw::kLeftSwitchState,
                                sw::kRightStopDisable, sw::kLeftStopDisable, kMinSpeed, kActualAcceleration,
                                kRampMode, kApMicrostepResolution, kSoftStop, kRampDivisor, kPulseDivisor, kLastReferencePosition,
                                sw::kRfsMode, sw::kRfsSpeed, sw::kRfsSwitchSpeed, sw::kRfsDistance,
                                sw::kErrorFlags, sw::kEncoderPosition, sw::kEncoderPrescaler, sw::kMaxDeviation,
                                // stallGuard2 (stall_core.cpp): run current, filter, threshold, stop on stall, load value, driver flags
                                6, 173, 174, 181, 206, 208,
                                // coolStep (coolstep_core.cpp): standby current, 168-172, actual current, threshold speed
                                7, 168, 169, 170, 171, 172, 180, 182,
                                sw::kSg1Threshold};  // the TMCM-351's stallGuard 1 (stall_core.cpp)

class Tmc429Core final : public sw::SwitchCore {
 public:
  std::string_view name() const override { return "tmc429"; }
  std::unique_ptr<MotionCore> clone() const override { return std::make_unique<Tmc429Core>(*this); }

  // Its parameters are in the chip's units: their rows and defaults come from the TMCM-1110's
  // profile wherever the active one (generic) has them in pps or not at all. The home switch is
  // in series with the left one (TMCM-1110 manual, 5.3).
  Tmc429Core() : SwitchCore(kTmc429Owned, "tmcm-1110", true, {kSoftStop, true, false, kLastReferencePosition}) {}

  void reset(const Profile& profile, int motors) override {
    SwitchCore::reset(profile, motors);
    const Profile* units = profile.any_parameter ? find_profile("tmcm-1110") : &profile;  // generic: the TMC429's
    clock_ = static_cast<double>(units ? units->motion_constant("clock", 16'000'000) : 16'000'000);
    velocity_divisor_ = static_cast<double>(units ? units->motion_constant("velocity-divisor", 65536) : 65536);
    acceleration_shift_ = static_cast<int>(units ? units->motion_constant("acceleration-shift", 29) : 29);
  }

  std::int32_t get_param(int motor, int param) override {
    if (param != kActualAcceleration) return SwitchCore::get_param(motor, param);
    const sw::Motor& m = at(motor);
    return units(std::fabs(m.rm.state(now_).a) / aunit(m));
  }

  // The chip's ramp mode (138) follows the commands.
  void move_absolute(int motor, std::int32_t target) override {
    sw::Motor& m = at(motor);
    m.p[kRampMode] = m.p[kRampMode] == 1 ? 1 : 0;
    SwitchCore::move_absolute(motor, target);
  }
  void rotate(int motor, std::int32_t velocity) override {
    at(motor).p[kRampMode] = 2;
    SwitchCore::rotate(motor, velocity);
  }
  void stop(int motor) override {
    sw::Motor& m = at(motor);
    if (m.goal == Goal::Idle && m.rm.at_rest(now_)) return;
    m.p[kRampMode] = 2;
    SwitchCore::stop(motor);
  }

  std::optional<PhysicalValue> physical(int motor, int param, std::int32_t raw) const override {
    const sw::Motor& m = motors_[static_cast<std::size_t>(motor)];
    switch (param) {
      case kApTargetSpeed: case kApActualSpeed: case kApMaxPositioningSpeed: case kMinSpeed:
      case sw::kRfsSpeed: case sw::kRfsSwitchSpeed:
        return PhysicalValue{raw * vunit(m), "pps"};
      case kApMaxAcceleration: case kActualAcceleration: return PhysicalValue{raw * aunit(m), "pps²"};
      default: return std::nullopt;
    }
  }
  std::string units_note() const override {
    std::string note = "TMC429 units";
    auto one = [this](const sw::Motor& m) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "pulse divisor %d, ramp divisor %d: velocity 1 = %.6g pps, acceleration 1 = %.6g pps²",
                    m.p[kPulseDivisor], m.p[kRampDivisor], vunit(m), aunit(m));
      return std::string(buf);
    };
    bool same = std::all_of(motors_.begin(), motors_.end(), [&](const sw::Motor& m) {
      return m.p[kPulseDivisor] == motors_.front().p[kPulseDivisor] && m.p[kRampDivisor] == motors_.front().p[kRampDivisor];
    });
    if (motors_.empty()) return note;
    if (same) return note + ": " + one(motors_.front());
    for (std::size_t i = 0; i < motors_.size(); ++i) note += (i ? "; motor " : ": motor ") + std::to_string(i) + ": " + one(motors_[i]);
    return note;
  }

 protected:
  // pps per velocity unit and pps² per acceleration unit (TMCM-1110 manual 5.5).
  // The constants are the profile's (motion-constant lines), the manual's where it gives none.
  double vunit(const sw::Motor& m) const override { return std::ldexp(clock_ / velocity_divisor_, -m.p[kPulseDivisor]); }
  std::int32_t max_speed() const override { return kChipMax; }
  Limits ramp_limits(const sw::Motor& m) const override {
    return limits(m, clamp_units(m.p[kApMaxPositioningSpeed]), m.goal == Goal::Position);
  }
  Limits search_limits(const sw::Motor& m, std::int32_t speed, bool positioning) const override {
    return limits(m, clamp_units(speed), positioning);
  }
  void plan_position(sw::Motor& m, Builder& b, const Limits& lim) const override {
    if (m.p[kRampMode] != 1 || !plan_soft(m, b, lim)) SwitchCore::plan_position(m, b, lim);
  }
  // In position mode the chip sets 2 to the maximum speed while it speeds up or cruises and to 0
  // while it slows down or rests (manual, parameter 2).
  std::int32_t target_speed(const sw::Motor& m, const ramp::State& s) const override {
    if (m.goal != Goal::Position) return m.goal == Goal::Search ? 0 : m.vt;
    if (s.v == 0 || s.v * s.a < 0) return 0;
    return s.v > 0 ? m.p[kApMaxPositioningSpeed] : -m.p[kApMaxPositioningSpeed];
  }
  // 9 is the reference input: the left switch or the home switch in series with it.
  bool home_state(const sw::Motor& m) const override { return closed(m, sw::kRefInput); }

  ParamWrite set_other(sw::Motor& m, int param, std::int32_t value) override {
    switch (param) {
      case kActualAcceleration: return ParamWrite::ReadOnly;
      case kRampMode:  // the chip drives to the target (0, 1) or at the target speed (2) at once
        if (!in_range(param, value)) return ParamWrite::OutOfRange;
        m.p[kRampMode] = value;
        abort_search(m);
        if (value != 2 && m.goal == Goal::Idle && target_reached(index(m))) return ParamWrite::Ok;  // nothing to do
        m.goal = value == 2 ? Goal::Velocity : Goal::Position;
        if (value == 2) m.vt = m.p[kApTargetSpeed];
        m.trip_t = ramp::kInf;
        replan(m);
        return ParamWrite::Ok;
      case kPulseDivisor: case kApMicrostepResolution: {
        if (!in_range(param, value)) return ParamWrite::OutOfRange;
        const double fv_before = vunit(m);
        const std::int32_t before = m.p[static_cast<std::size_t>(param)];
        m.p[static_cast<std::size_t>(param)] = value;
        // The chip keeps its actual velocity in units: a new pulse divisor changes the step rate at once.
        if (param == kPulseDivisor && before != value) replan(m, vunit(m) / fv_before);
        return ParamWrite::Ok;
      }
      default: return SwitchCore::set_other(m, param, value);
    }
  }

 private:
  double aunit(const sw::Motor& m) const {
    return std::ldexp(clock_ * clock_, -(m.p[kPulseDivisor] + m.p[kRampDivisor] + acceleration_shift_));
  }
  double clock_ = 16e6, velocity_divisor_ = 65536;  // fCLK (Hz), 2048 · 32: TMCM-1110 manual 5.5
  int acceleration_shift_ = 29;
  static double clamp_units(std::int32_t v) { return std::clamp(v, 0, kChipMax); }
  int index(const sw::Motor& m) const { return static_cast<int>(&m - motors_.data()); }

  // A positioning ramp at `vmax` units: one acceleration both ways, the minimum speed (130) as
  // start and stop speed. A velocity ramp starts from and stops to 0.
  Limits limits(const sw::Motor& m, double vmax, bool positioning) const {
    const double fv = vunit(m), a = clamp_units(m.p[kApMaxAcceleration]) * aunit(m);
    Limits l;
    l.vmax = std::min<double>(vmax, kChipMax) * fv;
    l.amax = l.astart = l.dmax = l.dfinal = a;
    if (positioning) l.vstart = l.vstop = std::min<double>(clamp_units(m.p[kMinSpeed]), vmax) * fv;
    return l;
  }

  // Soft mode (138 = 1): a positioning whose approach slows exponentially. Within vp/k of the
  // target the speed is k times the distance left, k = a_max / V_MAX (so the slowing starts with
  // at most a_max), down to the minimum speed (130), which runs the last 1/k seconds onto the
  // target. With minimum speed 0 the speed falls below one unit short of the target and the chip's
  // whole units make it 0 there: the motor stops short and the target is not reached (hence the
  // manual's "should always be set 1"). The exponential is pieces of constant jerk, 1/20 of 1/k
  // each, that meet it in speed and place at their ends (the acceleration is off by 1e-3 of it at
  // most); the last cruise absorbs the rounding. False (nothing planned) when
  // the motion now does not fit the profile (moving away from the target, or too fast to enter
  // it): the position mode's ramp takes over.
  bool plan_soft(const sw::Motor& m, Builder& b, const Limits& lim) const {
    const ramp::State s = b.state();
    const double target = static_cast<double>(m.p[kApTargetPosition] - m.rm.base);
    const double dist = std::fabs(target - s.x), V = lim.vmax, a = lim.amax;
    const int dir = target > s.x ? 1 : -1;
    if (!lim.can_move() || dist < 0.5 || s.v * dir < 0 || (s.v == 0 && s.a != 0)) return false;
    const double u0 = s.v == 0 ? lim.vstart : std::fabs(s.v), k = a / V;
    const double vp = std::min(V, -V + std::sqrt(V * V + 2 * a * dist + u0 * u0));
    const double vend = lim.vstop > 0 ? lim.vstop : vunit(m);  // below one unit the chip reads 0
    if (vp < u0 * (1 - 1e-9) || vp <= vend) return false;  // (within the exponential vp = u0)
    if (!b.ramp_to(lim, dir * std::max(vp, u0))) return false;
    b.cruise((dist - std::fabs(b.state().x - s.x) - vp / k) / vp, dir);
    const double tau_all = std::log(vp / vend) / k;
    const int n = std::max(1, static_cast<int>(std::ceil(tau_all * k * 20)));
    const double tau = tau_all / n, fall = std::exp(-k * tau);
    double u = vp;
    for (int i = 0; i < n; ++i, u *= fall) {  // each piece ends on the exponential's speed and place
      const double dv = u * fall - u, dx = (u - u * fall) / k - u * tau;
      const double j = (6 * dv * tau - 12 * dx) / (tau * tau * tau);
      b.piece(tau, (dv - j * tau * tau / 2) / tau, j, dir);
    }
    if (lim.vstop <= 0) {  // stops short: no target reached
      b.stop_hard();
      b.finish_rest();
      return true;
    }
    b.cruise((dir * (target - b.state().x)) / lim.vstop, dir);
    b.arrive(target, dir);
    return true;
  }

};

}  // namespace

std::unique_ptr<MotionCore> make_tmc429_motion_core() { return std::make_unique<Tmc429Core>(); }

}  // namespace tmcl
