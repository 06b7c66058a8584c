// The `tmc429` motion core: the ramp generator of the TMCM-1110, -3110, -6110 and -351 (a TMC429)
// as their firmware manuals describe it. Speeds and accelerations are the chip's whole units,
// scaled by the pulse divisor (154) and the ramp divisor (153):
//   microstep rate  = fCLK * v / 2^(pulse_div + 16)            (2048 * 32 = 2^16)
//   acceleration    = fCLK^2 * a_max / 2^(pulse_div + ramp_div + 29)
// with fCLK = 16 MHz (TMCM-1110 manual, section 5.5). Trapezoid ramps with one acceleration both
// ways and the minimum speed (130) as start and stop speed, velocity mode, re-targeting from the
// current state (the closed-form planner of ramp.hpp), the limit switches with their stop
// functions (12, 13: disable; 149: soft stop), and the modules' reference search (RFS, 193-196)
// as a state machine driven by the switches. docs/motion.md explains every decision.
//
// Parameters it owns: 0-5, 8-13, 130, 135, 138, 140, 149, 153, 154, 193-196.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "ramp_motor.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"

namespace tmcl {
namespace {

using ramp::Builder;
using ramp::EventKind;
using ramp::Limits;
using ramp::SwitchHit;

constexpr int kChipMax = 2047;         // velocity and acceleration registers: 11 bits

// The parameters of the TMC429 modules this core gives a meaning (TMCM-1110 manual, chapter 5).
enum Tmc429Param : int {
  kRefSwitchState = 9,     // the reference (left) input: left or home switch
  kRightSwitchState = 10,
  kLeftSwitchState = 11,
  kRightStopDisable = 12,
  kLeftStopDisable = 13,
  kMinSpeed = 130,
  kActualAcceleration = 135,
  kRampMode = 138,         // 0 position, 1 soft, 2 velocity
  kSoftStop = 149,         // 1: a stop switch stops with the ramp, 0: at once
  kRampDivisor = 153,
  kPulseDivisor = 154,
  kRfsMode = 193,          // 1-8, +128 reverses the home switch's polarity
  kRfsSpeed = 194,
  kRfsSwitchSpeed = 195,
  kRfsDistance = 196,      // right switch to reference point, after modes 2 and 3
};

constexpr int kTmc429Owned[] = {kApTargetPosition, kApActualPosition, kApTargetSpeed, kApActualSpeed,
                                kApMaxPositioningSpeed, kApMaxAcceleration, kApPositionReached,
                                kRefSwitchState, kRightSwitchState, kLeftSwitchState, kRightStopDisable,
                                kLeftStopDisable, kMinSpeed, kActualAcceleration, kRampMode,
                                kApMicrostepResolution, kSoftStop, kRampDivisor, kPulseDivisor, kRfsMode,
                                kRfsSpeed, kRfsSwitchSpeed, kRfsDistance};


enum class Tmc429Goal : std::uint8_t { Idle, Position, Velocity, Halt, Search };

// The reference search's steps (docs/motion.md has a figure per mode):
//   FindRight  modes 2, 3: toward + at the search speed until the right switch closes
//   Find       toward the switch at the search speed until it closes (modes 5, 6: the end switch
//              on the way reverses the search once)
//   Release    back at the switch speed until it opens: its near edge
//   Reenter    toward it again until it closes: the edge once more
//   Cross      on through it until it opens at its far edge (switches with two edges)
//   ToRef      to the reference point, which is then position 0
enum class SearchStep : std::uint8_t { Off, FindRight, Find, Release, Reenter, Cross, ToRef };
constexpr int kRefInput = 3;  // mode 3: the reference input, the left or the home switch

struct Tmc429Search {
  SearchStep step = SearchStep::Off;
  int mode = 0;          // 1-8
  bool invert = false;   // +128: the home switch is closed outside its range
  int input = 0;         // SwitchInput searched, or kRefInput
  int dir = -1;          // direction of the current step
  int reverse_at = -1;   // modes 5, 6: the end switch that turns the search around (-1: none)
  bool both = false;     // the switch has a far edge: calibrate from both sides
  std::int64_t right = 0, release = 0, reenter = 0;  // switching points (register counts)
};

struct Tmc429Motor {
  ramp::RampMotor rm;
  std::array<std::int32_t, 256> p{};  // owned parameters, raw as written
  Tmc429Goal goal = Tmc429Goal::Idle;
  std::int32_t vt = 0;                // velocity-mode target, chip units
  std::uint8_t timed = 0;             // bit (1 << SwitchInput): closed by a timed scenario line
  double trip_t = ramp::kInf;         // plan instant of a pending limit-switch stop
  Tmc429Search search;
};

class Tmc429Core final : public ramp::RampCore<Tmc429Motor> {
 public:
  std::string_view name() const override { return "tmc429"; }
  std::unique_ptr<MotionCore> clone() const override { return std::make_unique<Tmc429Core>(*this); }

  // Its parameters are in the chip's units: their rows and defaults come from the TMCM-1110's
  // profile wherever the active one (generic) has them in pps or not at all.
  Tmc429Core() : RampCore(kTmc429Owned, "tmcm-1110", true) {}

  void reset(const Profile& profile, int motors) override {
    RampCore::reset(profile, motors);
    const Profile* units = profile.any_parameter ? find_profile("tmcm-1110") : &profile;  // generic: the TMC429's
    clock_ = static_cast<double>(units ? units->motion_constant("clock", 16'000'000) : 16'000'000);
    velocity_divisor_ = static_cast<double>(units ? units->motion_constant("velocity-divisor", 65536) : 65536);
    acceleration_shift_ = static_cast<int>(units ? units->motion_constant("acceleration-shift", 29) : 29);
  }

  void advance(SimTime to, std::vector<MotionEvent>& out) override {
    collect(
        to, out,
        [](Tmc429Motor& m, EventKind k) {
          if (k == EventKind::ReferenceDone) m.search.step = SearchStep::Off;
          if (k != EventKind::VelocityReached) m.goal = Tmc429Goal::Idle, m.trip_t = ramp::kInf;
        },
        [this](Tmc429Motor& m, const SwitchHit& h) {
          if (m.goal == Tmc429Goal::Search) search_switch(m, h.input, h.in, h.edge, h.dir);
        });
  }

  ParamWrite set_param(int motor, int param, std::int32_t value) override {
    Tmc429Motor& m = at(motor);
    switch (param) {
      case kApTargetPosition: move_absolute(motor, value); return ParamWrite::Ok;
      case kApActualPosition:  // shifts the register; a move in progress still goes to its target
        m.rm.shift(static_cast<std::int64_t>(value) - m.rm.xactual(now_));
        if (m.goal == Tmc429Goal::Position) replan(m);
        return ParamWrite::Ok;
      case kApTargetSpeed:
        if (!in_range(param, value)) return ParamWrite::OutOfRange;
        rotate(motor, value);
        return ParamWrite::Ok;
      case kApActualSpeed: case kApPositionReached: case kRefSwitchState: case kRightSwitchState:
      case kLeftSwitchState: case kActualAcceleration: case kRfsDistance:
        return ParamWrite::ReadOnly;
      case kRampMode:  // the chip drives to the target (0, 1) or at the target speed (2) at once
        if (!in_range(param, value)) return ParamWrite::OutOfRange;
        m.p[kRampMode] = value;
        abort_search(m);
        if (value != 2 && m.goal == Tmc429Goal::Idle && target_reached(motor)) return ParamWrite::Ok;  // nothing to do
        m.goal = value == 2 ? Tmc429Goal::Velocity : Tmc429Goal::Position;
        if (value == 2) m.vt = m.p[kApTargetSpeed];
        m.trip_t = ramp::kInf;
        replan(m);
        return ParamWrite::Ok;
      case kRfsMode:
        if (!in_range(param, value) || (value & 127) < 1 || (value & 127) > 8) return ParamWrite::OutOfRange;
        break;
      default:
        if (!in_range(param, value)) return ParamWrite::OutOfRange;  // the profile's range (core_skeleton.hpp)
        break;
    }
    const std::int32_t before = m.p[static_cast<std::size_t>(param)];
    const double fv_before = vunit(m);
    m.p[static_cast<std::size_t>(param)] = value;
    if (before == value) return ParamWrite::Ok;
    // The chip keeps its actual velocity in units: a new pulse divisor changes the step rate at once.
    if (param == kPulseDivisor) return replan(m, vunit(m) / fv_before), ParamWrite::Ok;
    if (param != kApMicrostepResolution && param != kRfsMode) replan(m);
    return ParamWrite::Ok;
  }

  std::int32_t get_param(int motor, int param) override {
    Tmc429Motor& m = at(motor);
    const ramp::State s = m.rm.state(now_);
    switch (param) {
      case kApActualPosition: return ramp::wrap32(m.rm.xactual(now_));
      case kApTargetSpeed: return target_speed(m, s);
      case kApActualSpeed: return units(s.v / vunit(m));
      case kActualAcceleration: return units(std::fabs(s.a) / aunit(m));
      case kApPositionReached: return target_reached(motor) ? 1 : 0;
      case kRefSwitchState: return closed(m, 0) || closed(m, 2) ? 1 : 0;
      case kRightSwitchState: return closed(m, 1) ? 1 : 0;
      case kLeftSwitchState: return closed(m, 0) ? 1 : 0;
      default: return m.p[static_cast<std::size_t>(param)];
    }
  }

  void move_absolute(int motor, std::int32_t target) override {
    Tmc429Motor& m = at(motor);
    abort_search(m);
    m.p[kApTargetPosition] = target;
    m.p[kRampMode] = m.p[kRampMode] == 1 ? 1 : 0;
    m.goal = Tmc429Goal::Position;
    m.trip_t = ramp::kInf;
    replan(m);
  }
  // MVP REL counts from the last target (the TMC429 modules have no parameter 127).
  void move_relative(int motor, std::int32_t offset) override {
    move_absolute(motor, ramp::wrap32(static_cast<std::int64_t>(at(motor).p[kApTargetPosition]) + offset));
  }
  void rotate(int motor, std::int32_t velocity) override {
    Tmc429Motor& m = at(motor);
    abort_search(m);
    m.vt = std::clamp(velocity, -kChipMax, kChipMax);  // the chip's register holds no more
    m.p[kRampMode] = 2;
    m.goal = Tmc429Goal::Velocity;
    m.trip_t = ramp::kInf;
    replan(m);
  }
  void stop(int motor) override {
    Tmc429Motor& m = at(motor);
    if (m.goal == Tmc429Goal::Idle && m.rm.at_rest(now_)) return;
    abort_search(m);
    m.vt = 0;
    m.p[kRampMode] = 2;
    m.goal = Tmc429Goal::Velocity;
    m.trip_t = ramp::kInf;
    replan(m);
  }

  std::int32_t reference_search(int motor, RfsAction action) override {
    Tmc429Motor& m = at(motor);
    switch (action) {
      case RfsAction::Start: start_search(m); return 0;
      case RfsAction::Stop:
        if (m.search.step != SearchStep::Off) stop(motor);
        return 0;
      case RfsAction::Status: return m.search.step != SearchStep::Off ? 1 : 0;
    }
    return 0;
  }
  bool reference_done(int motor) const override {
    return motors_[static_cast<std::size_t>(motor)].search.step == SearchStep::Off;
  }

  void set_switch(int motor, SwitchInput input, bool active) override {
    Tmc429Motor& m = at(motor);
    const int k = static_cast<int>(input);
    const bool was = closed(m, k);
    const auto bit = static_cast<std::uint8_t>(1u << k);
    m.timed = static_cast<std::uint8_t>(active ? m.timed | bit : m.timed & ~bit);
    if (closed(m, k) == was) return;
    if (m.goal == Tmc429Goal::Search)  // a timed switch has no place: its edge is where the motor is
      search_switch(m, k, closed(m, k), m.rm.xactual(now_), 0);
    else if (active && (m.goal == Tmc429Goal::Position || m.goal == Tmc429Goal::Velocity))
      replan(m);  // the trip scan stops the motor at once if it moves toward the switch
  }
  void encoder_slip(int, std::int32_t) override {}  // the encoder is not modelled (docs/motion.md)

  std::optional<PhysicalValue> physical(int motor, int param, std::int32_t raw) const override {
    const Tmc429Motor& m = motors_[static_cast<std::size_t>(motor)];
    switch (param) {
      case kApTargetSpeed: case kApActualSpeed: case kApMaxPositioningSpeed: case kMinSpeed:
      case kRfsSpeed: case kRfsSwitchSpeed:
        return PhysicalValue{raw * vunit(m), "pps"};
      case kApMaxAcceleration: case kActualAcceleration: return PhysicalValue{raw * aunit(m), "pps²"};
      default: return std::nullopt;
    }
  }
  std::string units_note() const override {
    std::string note = "TMC429 units";
    auto one = [this](const Tmc429Motor& m) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "pulse divisor %d, ramp divisor %d: velocity 1 = %.6g pps, acceleration 1 = %.6g pps²",
                    m.p[kPulseDivisor], m.p[kRampDivisor], vunit(m), aunit(m));
      return std::string(buf);
    };
    bool same = std::all_of(motors_.begin(), motors_.end(), [&](const Tmc429Motor& m) {
      return m.p[kPulseDivisor] == motors_.front().p[kPulseDivisor] && m.p[kRampDivisor] == motors_.front().p[kRampDivisor];
    });
    if (motors_.empty()) return note;
    if (same) return note + ": " + one(motors_.front());
    for (std::size_t i = 0; i < motors_.size(); ++i) note += (i ? "; motor " : ": motor ") + std::to_string(i) + ": " + one(motors_[i]);
    return note;
  }

 private:
  // pps per velocity unit and pps² per acceleration unit (TMCM-1110 manual 5.5).
  // The constants are the profile's (motion-constant lines), the manual's where it gives none.
  double vunit(const Tmc429Motor& m) const { return std::ldexp(clock_ / velocity_divisor_, -m.p[kPulseDivisor]); }
  double aunit(const Tmc429Motor& m) const {
    return std::ldexp(clock_ * clock_, -(m.p[kPulseDivisor] + m.p[kRampDivisor] + acceleration_shift_));
  }
  double clock_ = 16e6, velocity_divisor_ = 65536;  // fCLK (Hz), 2048 · 32: TMCM-1110 manual 5.5
  int acceleration_shift_ = 29;
  // A reading in whole units, toward zero as the chip's registers hold it.
  static std::int32_t units(double v) { return static_cast<std::int32_t>(std::trunc(v + (v > 0 ? 1e-9 : -1e-9))); }
  static double clamp_units(std::int32_t v) { return std::clamp(v, 0, kChipMax); }

  // In position mode the chip sets 2 to the maximum speed while it speeds up or cruises and to 0
  // while it slows down or rests (manual, parameter 2).
  std::int32_t target_speed(const Tmc429Motor& m, const ramp::State& s) const {
    if (m.goal != Tmc429Goal::Position) return m.goal == Tmc429Goal::Search ? 0 : m.vt;
    if (s.v == 0 || s.v * s.a < 0) return 0;
    return s.v > 0 ? m.p[kApMaxPositioningSpeed] : -m.p[kApMaxPositioningSpeed];
  }

  // A positioning ramp at `vmax` units: one acceleration both ways, the minimum speed (130) as
  // start and stop speed. A velocity ramp starts from and stops to 0.
  Limits limits(const Tmc429Motor& m, double vmax, bool positioning) const {
    const double fv = vunit(m), a = clamp_units(m.p[kApMaxAcceleration]) * aunit(m);
    Limits l;
    l.vmax = std::min<double>(vmax, kChipMax) * fv;
    l.amax = l.astart = l.dmax = l.dfinal = a;
    if (positioning) l.vstart = l.vstop = std::min<double>(clamp_units(m.p[kMinSpeed]), vmax) * fv;
    return l;
  }
  Limits ramp_limits(const Tmc429Motor& m) const {
    return limits(m, clamp_units(m.p[kApMaxPositioningSpeed]), m.goal == Tmc429Goal::Position);
  }

  bool closed(const Tmc429Motor& m, int input) const {
    if (input == kRefInput) return closed(m, 0) || closed(m, 2);
    return ((m.timed >> input) & 1) || m.rm.zones[static_cast<std::size_t>(input)].in;
  }

  // Re-plans motor m from its state now toward its goal; then the first limit-switch trip cuts it.
  void replan(Tmc429Motor& m, double vscale = 1) {
    if (m.goal == Tmc429Goal::Search) return search_step(m, false, vscale);
    if (m.trip_t != ramp::kInf && m.rm.secs(now_) >= m.trip_t && m.goal != Tmc429Goal::Idle)
      m.goal = Tmc429Goal::Halt;  // the switch was hit: what is left is its stop
    m.trip_t = ramp::kInf;
    if (m.goal == Tmc429Goal::Idle) return;
    Limits lim = ramp_limits(m);
    Builder b = m.rm.restart(now_, vscale);
    switch (m.goal) {
      case Tmc429Goal::Position:
        if (m.p[kRampMode] != 1 || !plan_soft(m, b, lim))
          b.plan_position(lim, static_cast<double>(m.p[kApTargetPosition] - m.rm.base));
        break;
      case Tmc429Goal::Velocity: b.plan_velocity(lim, m.vt * vunit(m)); break;
      case Tmc429Goal::Halt: return switch_stop(m, b, lim);
      default: break;
    }
    scan_trips(m, lim);
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
  bool plan_soft(const Tmc429Motor& m, Builder& b, const Limits& lim) const {
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

  // A limit switch stops the motor with the ramp (149 = 1) or at once (149 = 0).
  void switch_stop(Tmc429Motor& m, Builder& b, const Limits& lim) {
    if (m.p[kSoftStop])
      b.stop_ramp(lim);
    else
      b.stop_hard();
    b.event(EventKind::Stopped);
    b.finish_rest();
  }

  // The first instant the plan moves toward a closed limit switch or reaches a placed one whose
  // stop function is on (12, 13 = 0): there the plan is cut and the stop appended.
  void scan_trips(Tmc429Motor& m, const Limits& lim) {
    const bool left_on = m.p[kLeftStopDisable] == 0, right_on = m.p[kRightStopDisable] == 0;
    if (!left_on && !right_on) return;
    for (const auto& seg : m.rm.plan.segs) {
      if (seg.dir == 0) continue;
      const int input = seg.dir < 0 ? 0 : 1;
      if (!(seg.dir < 0 ? left_on : right_on)) continue;
      double dt = (m.timed >> input) & 1 ? 0.0 : m.rm.entry(seg, input);
      if (dt < 0) continue;
      m.trip_t = seg.t0 + dt;
      Builder b(m.rm.plan, {}, 0);
      b.truncate(m.trip_t);
      switch_stop(m, b, lim);
      m.rm.rest_on_grid();
      return;
    }
  }

  // ---------------------------------------------------------------- reference search

  std::int32_t search_speed(const Tmc429Motor& m) const {
    return m.p[kRfsSpeed] ? m.p[kRfsSpeed] : m.p[kApMaxPositioningSpeed];
  }
  std::int32_t switch_speed(const Tmc429Motor& m) const {
    return m.p[kRfsSwitchSpeed] ? m.p[kRfsSwitchSpeed] : m.p[kApMaxPositioningSpeed] / 4;
  }
  // Whether the searched switch is closed (mode + 128: the home switch reads inverted).
  bool search_closed(const Tmc429Motor& m, int input) const {
    if (input == kRefInput) return closed(m, 0) || search_closed(m, 2);
    return closed(m, input) != (input == 2 && m.search.invert);
  }

  void start_search(Tmc429Motor& m) {
    Tmc429Search& s = m.search;
    s = Tmc429Search{};
    s.mode = m.p[kRfsMode] & 127;
    s.invert = (m.p[kRfsMode] & 128) != 0;
    if (s.mode < 1 || s.mode > 8) s.mode = 1;
    s.step = s.mode == 2 || s.mode == 3 ? SearchStep::FindRight : SearchStep::Find;
    s.input = s.mode <= 2 || s.mode == 4 ? 0 : s.mode == 3 ? kRefInput : 2;
    s.dir = s.step == SearchStep::FindRight || s.mode == 6 || s.mode == 7 ? 1 : -1;
    s.reverse_at = s.mode == 5 ? 0 : s.mode == 6 ? 1 : -1;
    m.goal = Tmc429Goal::Search;
    m.trip_t = ramp::kInf;
    search_step(m, false);
  }

  void abort_search(Tmc429Motor& m) { m.search.step = SearchStep::Off; }

  // Starts the current step from the motor's state now. `stop_first`: the step begins at a switch
  // just met, so the motor first stops as 149 says (hard: at once; soft: the ramp of the turn).
  void search_step(Tmc429Motor& m, bool stop_first, double vscale = 1) {
    Tmc429Search& s = m.search;
    Builder b = m.rm.restart(now_, vscale);
    if (stop_first && !m.p[kSoftStop]) b.stop_hard();
    if (s.step == SearchStep::ToRef) {
      b.plan_position(limits(m, clamp_units(switch_speed(m)), true), static_cast<double>(-m.rm.base));
      auto& ev = m.rm.plan.events;  // none when the ramp cannot move (a_max or the speed 0)
      if (!ev.empty()) ev.back().kind = EventKind::ReferenceDone;  // the arrival ends the search
      return;
    }
    const bool fast = s.step == SearchStep::Find || s.step == SearchStep::FindRight;
    const double speed = clamp_units(fast ? search_speed(m) : switch_speed(m)) * vunit(m);
    b.plan_velocity(limits(m, kChipMax, false), s.dir * speed);
    m.rm.plan.events.clear();  // the search's own stops and speeds are no events of the program
    // A switch already as the step awaits it counts at once (e.g. a search started inside it).
    if (s.step == SearchStep::Find && s.reverse_at >= 0 && closed(m, s.reverse_at)) return turn_around(m);
    int input = s.step == SearchStep::FindRight ? 1 : s.input;
    bool want = s.step != SearchStep::Release && s.step != SearchStep::Cross;
    if (search_closed(m, input) == want) search_met(m, m.rm.xactual(now_));
  }

  // Modes 5 and 6: the end switch on the way turns the search around, once.
  void turn_around(Tmc429Motor& m) {
    m.search.reverse_at = -1;
    m.search.dir = -m.search.dir;
    search_step(m, true);
  }

  // A switch closed or opened during the search: `edge` is where (register counts), `dir` the
  // motor's direction then (0: at rest, or a timed switch).
  void search_switch(Tmc429Motor& m, int input, bool now_closed, std::int64_t edge, int dir) {
    Tmc429Search& s = m.search;
    if (s.step == SearchStep::Off || s.step == SearchStep::ToRef || (dir != 0 && dir != s.dir)) return;
    if (s.step == SearchStep::Find && input == s.reverse_at && now_closed) return turn_around(m);
    int awaited = s.step == SearchStep::FindRight ? 1 : s.input;
    if (awaited == kRefInput ? input == 1 : input != awaited) return;
    if (input == 2 && s.invert) now_closed = !now_closed;
    if (awaited == kRefInput) now_closed = search_closed(m, kRefInput);
    bool want = s.step != SearchStep::Release && s.step != SearchStep::Cross;
    if (now_closed == want) search_met(m, edge);
  }

  // The awaited switching happened at `edge`: record it and go on to the next step.
  void search_met(Tmc429Motor& m, std::int64_t edge) {
    Tmc429Search& s = m.search;
    switch (s.step) {
      case SearchStep::FindRight:
        s.right = edge;
        s.step = SearchStep::Find;
        s.dir = -1;
        return search_step(m, true);
      case SearchStep::Find:
        if (s.input == kRefInput) s.input = search_closed(m, 2) ? 2 : 0;  // mode 3: whichever it was
        s.both = far_edge(m, s.input, s.dir);
        s.step = SearchStep::Release;
        s.dir = -s.dir;
        return search_step(m, true);
      case SearchStep::Release:
        s.release = edge;
        s.step = SearchStep::Reenter;
        s.dir = -s.dir;
        return search_step(m, true);
      case SearchStep::Reenter:
        s.reenter = edge;
        if (s.both) {  // on through the switch, without stopping, to its far edge
          s.step = SearchStep::Cross;
          return;
        }
        return reference_at(m, s.release, s.reenter);
      case SearchStep::Cross: return reference_at(m, s.reenter, edge);
      default: return;
    }
  }

  // Whether the switch has an edge beyond the one met moving `dir`: a range (a home switch, a
  // cam on a stop input), not a stop switch that stays closed to the end of travel.
  bool far_edge(const Tmc429Motor& m, int input, int dir) const {
    const ramp::Zone& z = m.rm.zones[static_cast<std::size_t>(input)];
    if (!z.placed || (input == 2 && m.search.invert)) return false;
    return dir < 0 ? z.lo != INT64_MIN : z.hi != INT64_MAX;
  }

  // The reference point is the centre of the two switching points (rounded down): the register
  // counts from it from now on, 196 holds the distance from the right switch (modes 2 and 3), and
  // the motor goes there at the switch speed.
  void reference_at(Tmc429Motor& m, std::int64_t a, std::int64_t b) {
    Tmc429Search& s = m.search;
    const std::int64_t sum = a + b, ref = sum >= 0 ? sum / 2 : -((1 - sum) / 2);
    if (s.mode == 2 || s.mode == 3)
      m.p[kRfsDistance] = static_cast<std::int32_t>(std::clamp<std::int64_t>(s.right - ref, 0, INT32_MAX));
    m.rm.shift(-ref);
    m.p[kApTargetPosition] = 0;
    s.step = SearchStep::ToRef;
    search_step(m, true);
  }
};

}  // namespace

std::unique_ptr<MotionCore> make_tmc429_motion_core() { return std::make_unique<Tmc429Core>(); }

}  // namespace tmcl
