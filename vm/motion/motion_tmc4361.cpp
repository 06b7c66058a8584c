// The `tmc4361` motion core: the USB-2-SD's ramp generator (a TMC4361A-style motion controller)
// as the module's axis parameters expose it. Trapezoid/SixPoint and S-shaped positioning ramps,
// velocity mode, re-planning of a move when its target, speed or acceleration changes, virtual
// stops, stop switches, and the encoder with its deviation check. Every command computes a
// closed-form plan (ramp.hpp); time only evaluates it. docs/motion.md explains every decision.
//
// Parameters it owns: 0-5, 8-11, 14-29, 35, 127, 131, 132, 140, 202, 207, 209, 210, 212, 251, 255
// (9-11, the switch states, are the TMCM-3351's and -3312's: the USB-2-SD has no such rows).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "ramp_motor.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"

namespace tmcl {
namespace {

using ramp::Builder;
using ramp::EventKind;
using ramp::Limits;
using ramp::RampMotor;

// The switch states of the TMCM modules with this controller (TMCM-3351, -3312), as the TMCM
// cores number them (switch_core.hpp): the home, right and left switch.
enum SwitchState : int { kHomeState = 9, kRightState = 10, kLeftState = 11 };

constexpr int kTmc4361Owned[] = {kApTargetPosition,    kApActualPosition,      kApTargetSpeed,
                          kApActualSpeed,       kApMaxPositioningSpeed, kApMaxAcceleration,
                          kApPositionReached,   kApRampType,            kApStartVelocity,
                          kApStartAcceleration, kApMaxDeceleration,     kApBreakVelocity,
                          kApFinalDeceleration, kApStopVelocity,        kApStopDeceleration,
                          kApBow1,              kApBow2,                kApBow3,
                          kApBow4,              kApVirtualStopLeft,     kApVirtualStopRight,
                          kApVirtualStopEnable, kApVirtualStopMode,     kApBowScalingFactor,
                          kApRelativePositioningOption, kApMeasuredSpeed, kApCurrentMeasuredSpeed,
                          kApMicrostepResolution, kApFullStepResolution, kApExtendedErrorFlags,
                          kApEncoderPosition,   kApEncoderResolution,   kApMaxEncoderDeviation,
                          kApReverseShaft,      kApUnitMode,
                          // last: owns() searches this list, and only the TMCM-3351 and -3312 have them
                          kHomeState,           kRightState,            kLeftState};

enum class Tmc4361Goal : std::uint8_t { Idle, Position, Velocity, Halt };
enum class Halt : std::uint8_t { Switch, VirtualStop, Deviation };

struct Tmc4361Motor {
  RampMotor rm;
  std::array<std::int32_t, 256> p{};  // owned parameters, raw as written
  Tmc4361Goal goal = Tmc4361Goal::Idle;
  std::int32_t vt = 0;                // velocity-mode target, raw (param 2)
  Halt halt = Halt::Switch;           // which stop a Halt goal is
  double trip_t = ramp::kInf;         // plan instant of a pending trip (switch, virtual stop, ...)
  Halt trip_kind = Halt::Switch;
  bool left = false, right = false, home = false;
  std::int64_t enc_off = 0;           // encoder position = s * XACTUAL + enc_off
  std::int32_t errors = 0;            // parameter 207
};

class Tmc4361Core final : public ramp::RampCore<Tmc4361Motor> {
 public:
  std::string_view name() const override { return "tmc4361"; }
  std::unique_ptr<MotionCore> clone() const override { return std::make_unique<Tmc4361Core>(*this); }

  Tmc4361Core() : RampCore(kTmc4361Owned, "usb-2-sd") {}  // the TMC4361 drives the USB-2-SD

  void advance(SimTime to, std::vector<MotionEvent>& out) override {
    collect(to, out, [](Tmc4361Motor& m, EventKind k) {
      if (k == EventKind::Deviation) m.errors = 2;
      if (k != EventKind::VelocityReached) m.goal = Tmc4361Goal::Idle, m.trip_t = ramp::kInf;
    });
  }

  ParamWrite set_param(int motor, int param, std::int32_t value) override {
    Tmc4361Motor& m = at(motor);
    switch (param) {
      case kApTargetPosition: move_absolute(motor, value); return ParamWrite::Ok;
      case kApActualPosition: {  // shift the coordinate system; a move in progress still goes to its target
        m.rm.shift(static_cast<std::int64_t>(value) - m.rm.xactual(now_));
        if (m.goal == Tmc4361Goal::Position) replan(m);
        return ParamWrite::Ok;
      }
      case kApTargetSpeed: rotate(motor, value); return ParamWrite::Ok;
      case kApActualSpeed: case kApPositionReached: case kHomeState: case kRightState: case kLeftState: case kApMeasuredSpeed: case kApCurrentMeasuredSpeed: case kApExtendedErrorFlags: return ParamWrite::ReadOnly;
      case kApEncoderPosition: m.enc_off = static_cast<std::int64_t>(value) - enc_sign(m) * m.rm.xactual(now_); break;
      case kApEncoderResolution: case kApReverseShaft: {  // keep the encoder reading, change how it follows the motor
        if (!in_range(param, value)) return ParamWrite::OutOfRange;
        std::int64_t e = encoder(m);
        m.p[static_cast<std::size_t>(param)] = value;
        m.enc_off = e - enc_sign(m) * m.rm.xactual(now_);
        break;
      }
      default: {
        if (!in_range(param, value)) return ParamWrite::OutOfRange;  // the profile's range (core_skeleton.hpp)
        Limits before = limits(m);
        m.p[static_cast<std::size_t>(param)] = value;
        Limits after = limits(m);
        bool ramp_changed = std::memcmp(&before, &after, sizeof before) != 0 || param == kApRampType || param == kApUnitMode;
        if (ramp_changed || (param >= kApVirtualStopLeft && param <= kApVirtualStopMode) || param == kApMaxEncoderDeviation) replan(m);
        return ParamWrite::Ok;
      }
    }
    m.p[static_cast<std::size_t>(param)] = value;
    if (param != kApEncoderPosition || m.goal != Tmc4361Goal::Idle) replan(m);
    return ParamWrite::Ok;
  }

  std::int32_t get_param(int motor, int param) override {
    Tmc4361Motor& m = at(motor);
    switch (param) {
      case kApActualPosition: return ramp::wrap32(m.rm.xactual(now_));
      case kApTargetSpeed: return m.vt;
      case kApActualSpeed: return speed_raw(m, m.rm.state(now_).v);
      case kApPositionReached: return target_reached(motor) ? 1 : 0;
      case kHomeState: return closed(m, SwitchInput::Home);
      case kRightState: return closed(m, SwitchInput::StopRight);
      case kLeftState: return closed(m, SwitchInput::StopLeft);
      case kApMeasuredSpeed: case kApCurrentMeasuredSpeed: return speed_raw(m, static_cast<double>(enc_sign(m)) * m.rm.state(now_).v);
      case kApExtendedErrorFlags: {
        std::int32_t e = m.errors;
        m.errors = 0;
        return e;
      }
      case kApEncoderPosition: return ramp::wrap32(encoder(m));
      default: return m.p[static_cast<std::size_t>(param)];
    }
  }

  void move_absolute(int motor, std::int32_t target) override {
    Tmc4361Motor& m = at(motor);
    m.p[kApTargetPosition] = target;
    m.errors = 0;
    m.goal = Tmc4361Goal::Position;
    m.trip_t = ramp::kInf;
    replan(m, true);
  }

  void rotate(int motor, std::int32_t velocity) override {
    Tmc4361Motor& m = at(motor);
    m.vt = velocity;
    m.errors = 0;
    m.goal = Tmc4361Goal::Velocity;
    m.trip_t = ramp::kInf;
    replan(m, true);
  }

  void stop(int motor) override {
    Tmc4361Motor& m = at(motor);
    if (m.goal == Tmc4361Goal::Idle && m.rm.at_rest(now_)) return;
    m.vt = 0;
    m.goal = Tmc4361Goal::Velocity;
    m.trip_t = ramp::kInf;
    replan(m);
  }

  // The USB-2-SD has no RFS; profiles that offer it (generic) get an instant reference search:
  // the motor stops where it is and that place becomes position 0 (encoder 0 too).
  std::int32_t reference_search(int motor, RfsAction action) override {
    if (action != RfsAction::Start) return 0;
    zero_here(motor);
    Tmc4361Motor& m = at(motor);
    m.enc_off = 0;
    m.goal = Tmc4361Goal::Idle;
    m.trip_t = ramp::kInf;
    return 0;
  }

  // Timed switches (set_switch) block motion toward them here; switches placed at positions
  // (place_switch, RampCore) stop it where the motor reaches them (scan_trips).
  void set_switch(int motor, SwitchInput input, bool active) override {
    Tmc4361Motor& m = at(motor);
    (input == SwitchInput::StopLeft ? m.left : input == SwitchInput::StopRight ? m.right : m.home) = active;
    if (input != SwitchInput::Home && active && (m.goal == Tmc4361Goal::Position || m.goal == Tmc4361Goal::Velocity)) replan(m);
  }

  bool models_encoder(const Profile&) const override { return true; }
  void encoder_slip(int motor, std::int32_t counts) override {
    Tmc4361Motor& m = at(motor);
    double res = std::abs(m.p[kApEncoderResolution]);
    double factor = res > 0 ? m.p[kApFullStepResolution] * std::ldexp(1.0, m.p[kApMicrostepResolution]) / res : 0;
    m.enc_off += std::llround(counts * factor);
    if (m.p[kApMaxEncoderDeviation] > 0 && std::llabs(deviation(m)) > m.p[kApMaxEncoderDeviation]) {
      if (m.goal == Tmc4361Goal::Position || m.goal == Tmc4361Goal::Velocity)
        replan(m);  // the trip scan finds the deviation at once
      else
        deviation_at_rest(m);
    }
  }

 private:
  // Unit mode 255: 1 = pps, pps², pps³; 0 = the ramp generator's fixed-point registers
  // (velocities 24.8, accelerations 22.2, bows unscaled).
  static double vunit(const Tmc4361Motor& m) { return m.p[kApUnitMode] ? 1.0 : 1.0 / 256; }
  static double aunit(const Tmc4361Motor& m) { return m.p[kApUnitMode] ? 1.0 : 1.0 / 4; }
  // A switch is closed while its timed input (set_switch) or its placed range (place_switch) says so.
  static std::int32_t closed(const Tmc4361Motor& m, SwitchInput input) {
    const bool timed = input == SwitchInput::StopLeft ? m.left : input == SwitchInput::StopRight ? m.right : m.home;
    return timed || m.rm.zones[static_cast<std::size_t>(input)].in ? 1 : 0;
  }
  static std::int32_t speed_raw(const Tmc4361Motor& m, double v) { return static_cast<std::int32_t>(std::trunc(v / vunit(m) + (v > 0 ? 1e-9 : -1e-9))); }

  // The effective ramp: 16, 17 = 0 mean "as 5", 19 = 0 means "as the effective 17" (profiles.md).
  static Limits limits(const Tmc4361Motor& m) {
    auto p = [&](int n) { return static_cast<double>(m.p[static_cast<std::size_t>(n)]); };
    const double vu = vunit(m), au = aunit(m);
    Limits l;
    l.vmax = p(kApMaxPositioningSpeed) * vu;
    l.amax = p(kApMaxAcceleration) * au;
    l.vstart = std::min(p(kApStartVelocity) * vu, l.vmax);
    l.vstop = p(kApStopVelocity) * vu;
    double dmax_raw = m.p[kApMaxDeceleration] ? p(kApMaxDeceleration) : p(kApMaxAcceleration);
    l.dmax = dmax_raw * au;
    if (m.p[kApRampType] == 1) {  // S-shaped: bows, no break velocity (16, 18, 19 are trapezoid settings)
      double scale = p(kApBowScalingFactor);
      auto inv = [&](int n) { return m.p[static_cast<std::size_t>(n)] > 0 ? 1.0 / (p(n) * scale) : 0.0; };
      l.ij1 = inv(kApBow1);
      l.ij2 = inv(kApBow2);
      l.ij3 = inv(kApBow3);
      l.ij4 = inv(kApBow4);
      l.astart = l.amax;
      l.dfinal = l.dmax;
    } else {
      l.vbreak = p(kApBreakVelocity) * vu;
      l.astart = (m.p[kApStartAcceleration] ? p(kApStartAcceleration) : p(kApMaxAcceleration)) * au;
      l.dfinal = (m.p[kApFinalDeceleration] ? p(kApFinalDeceleration) : dmax_raw) * au;
    }
    return l;
  }

  // Encoder direction relative to XACTUAL: reverse shaft turns the motor, not the encoder's
  // counting (manual, parameter 251); a negative resolution reverses the counting; 0 = none.
  static std::int64_t enc_sign(const Tmc4361Motor& m) {
    if (m.p[kApEncoderResolution] == 0) return 0;
    return (m.p[kApReverseShaft] ? -1 : 1) * (m.p[kApEncoderResolution] < 0 ? -1 : 1);
  }
  std::int64_t encoder(const Tmc4361Motor& m) const { return enc_sign(m) * m.rm.xactual(now_) + m.enc_off; }
  std::int64_t deviation(const Tmc4361Motor& m) const { return m.rm.xactual(now_) - encoder(m); }

  void deviation_at_rest(Tmc4361Motor& m) {
    Builder b = m.rm.restart(now_);
    b.stop_hard();
    b.event(EventKind::Deviation);
    b.finish_rest();
  }

  // Re-plans motor m from its state now toward its goal, then cuts the plan at the first trip.
  // A re-plan caused by a parameter or switch (not a command) of a motor already cruising at its
  // target speed does not report "velocity reached" again.
  void replan(Tmc4361Motor& m, bool by_command = false) {
    if (m.trip_t != ramp::kInf && m.rm.secs(now_) >= m.trip_t && m.goal != Tmc4361Goal::Idle) {
      m.goal = Tmc4361Goal::Halt;  // the trip already happened: what is left is its stop
      m.halt = m.trip_kind;
    }
    m.trip_t = ramp::kInf;
    if (m.goal == Tmc4361Goal::Idle) return;
    Limits lim = limits(m);
    Builder b = m.rm.restart(now_);
    switch (m.goal) {
      case Tmc4361Goal::Position: b.plan_position(lim, static_cast<double>(m.p[kApTargetPosition] - m.rm.base)); break;
      case Tmc4361Goal::Velocity: b.plan_velocity(lim, m.vt * vunit(m)); break;
      case Tmc4361Goal::Halt: return halt(m, b, lim, m.halt);
      case Tmc4361Goal::Idle: break;
    }
    if (!by_command && m.goal == Tmc4361Goal::Velocity && m.vt != 0) m.rm.drop_repeated_velocity_reached();
    scan_trips(m, lim);
  }

  void halt(Tmc4361Motor& m, Builder& b, const Limits& lim, Halt kind) {
    double dstop = m.p[kApStopDeceleration] * aunit(m);
    if (kind == Halt::Deviation) {
      b.stop_hard();
      b.event(EventKind::Deviation);
    } else {
      if (kind == Halt::VirtualStop && m.p[kApVirtualStopMode] == 0)
        b.stop_ramp(lim);
      else if (kind == Halt::VirtualStop && m.p[kApVirtualStopMode] == 1)
        b.stop_hard();
      else
        b.stop_linear(dstop);  // 0: hard
      b.event(EventKind::Stopped);
    }
    b.finish_rest();
  }

  // The first instant the new plan hits a stop switch in its direction, a virtual stop or the
  // encoder deviation limit; there the plan is cut and the stop appended.
  void scan_trips(Tmc4361Motor& m, const Limits& lim) {
    const auto& segs = m.rm.plan.segs;
    const double base = static_cast<double>(m.rm.base);
    const int vs_en = m.p[kApVirtualStopEnable];
    const std::int64_t maxdev = m.p[kApMaxEncoderDeviation];
    const std::int64_t c = 1 - enc_sign(m);  // deviation = c * XACTUAL - enc_off
    for (const auto& seg : segs) {
      if (seg.dir == 0) continue;
      double best = ramp::kInf;
      Halt kind = Halt::Switch;
      auto consider = [&](double dt, Halt k) {
        if (dt >= 0 && seg.t0 + dt < best) best = seg.t0 + dt, kind = k;
      };
      if ((seg.dir < 0 && m.left) || (seg.dir > 0 && m.right)) consider(0, Halt::Switch);
      if (m.rm.has_zones) consider(m.rm.entry(seg, seg.dir < 0 ? 0 : 1), Halt::Switch);  // a stop switch at a position
      if (seg.dir > 0 && (vs_en & 2)) consider(ramp::crossing(seg, m.p[kApVirtualStopRight] - base), Halt::VirtualStop);
      if (seg.dir < 0 && (vs_en & 1)) consider(ramp::crossing(seg, m.p[kApVirtualStopLeft] - base), Halt::VirtualStop);
      if (maxdev > 0) {
        if (c == 0) {
          if (std::llabs(m.enc_off) > maxdev) consider(0, Halt::Deviation);
        } else {  // the deviation grows with the position: a threshold in each direction
          double hi = std::floor(static_cast<double>(m.enc_off + maxdev) / static_cast<double>(c)) + 1;
          double lo = std::ceil(static_cast<double>(m.enc_off - maxdev) / static_cast<double>(c)) - 1;
          consider(ramp::crossing(seg, (seg.dir > 0 ? hi : lo) - base), Halt::Deviation);
        }
      }
      if (best != ramp::kInf) {
        m.trip_t = best;
        m.trip_kind = kind;
        Builder b(m.rm.plan, {}, 0);
        b.truncate(best);
        halt(m, b, lim, kind);
        m.rm.rest_on_grid();
        return;
      }
    }
  }
};

}  // namespace

std::unique_ptr<MotionCore> make_tmc4361_motion_core() { return std::make_unique<Tmc4361Core>(); }

}  // namespace tmcl
