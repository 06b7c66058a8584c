// The limit switches and the reference search of the TMCM modules' cores (switch_core.hpp).
#include "switch_core.hpp"

#include <algorithm>
#include <cmath>

#include "tmcl/params.hpp"

namespace tmcl::sw {

using ramp::Builder;
using ramp::EventKind;
using ramp::Limits;
using ramp::SwitchHit;

EncoderSpec EncoderSpec::of(const Profile& profile) {
  EncoderSpec e;
  e.present = profile.motion_constant("encoder", 0) != 0;
  e.prescaler_one = std::max<std::int64_t>(0, profile.motion_constant("encoder-prescaler", 0));
  e.prescaler_flags = static_cast<std::int32_t>(profile.motion_constant("encoder-prescaler-flags", 0));
  e.deviation_flag = static_cast<std::int32_t>(profile.motion_constant("deviation-flag", 0));
  e.flags_clear_on_read = profile.motion_constant("error-flags-read-clears", 0) != 0;
  return e;
}

// The encoder's facts come from the active profile, or under generic from the module the core
// models (as its units do).
void SwitchCore::reset(const Profile& profile, int motors) {
  RampCore::reset(profile, motors);
  const Profile* spec = profile.any_parameter ? find_profile(home_) : &profile;
  enc_spec_ = spec ? EncoderSpec::of(*spec) : EncoderSpec{};
  for (auto& m : motors_) set_prescaler(m);
  reset_stall(profile);
}

std::string SwitchCore::stop_reason(int motor) const {
  const Motor& m = motors_[static_cast<std::size_t>(motor)];
  if (m.halted_by == 0 || !m.rm.at_rest(now_) || m.goal != Goal::Idle) return {};
  return std::string(m.halted_by == 1 ? "stopped on stall (stop on stall, 181)" : "stopped on an encoder deviation beyond 212") +
         " at position " + std::to_string(ramp::wrap32(m.rm.xactual(now_))) + "; its target " +
         std::to_string(m.p[kApTargetPosition]) + " is kept";
}

MotionSample SwitchCore::sample_at(int motor, SimTime t) const {
  MotionSample s = RampCore::sample_at(motor, t);
  const Motor& m = motors_[static_cast<std::size_t>(motor)];
  // The shaft as it stands now (a hold or a release is an event: samples never pass one).
  const std::int64_t shaft = m.shaft.held ? m.shaft.held_at - m.rm.phys : s.position + m.shaft.offset;
  if (shaft != s.position) s.shaft = shaft;
  return s;
}

// The load value (206) and the actual current (180) as get_param would read them at t: the
// reading is the last measurement before t on the plan that holds until the next event, and
// coolStep's current changes only at events (CurrentChanged).
std::optional<std::int32_t> SwitchCore::sample_param(int motor, int param, SimTime t) const {
  if (param != 206 && param != 180) return std::nullopt;  // load value, actual current
  const Motor& m = motors_[static_cast<std::size_t>(motor)];
  if (std::int32_t v = 0; stall_param(m, param, v, t)) return v;
  if (param == 180 && cool_on_) return actual_current(m);
  return m.p[static_cast<std::size_t>(param)];
}

bool SwitchCore::models_encoder(const Profile& profile) const {
  const Profile* spec = profile.any_parameter ? find_profile(home_) : &profile;
  return spec && EncoderSpec::of(*spec).present;
}

// 210 as the prescaler: (value without the function bits) / encoder-prescaler.
void SwitchCore::set_prescaler(Motor& m) {
  if (!enc_spec_.present || enc_spec_.prescaler_one <= 0) return;
  m.enc.rescale(shaft_at(m), m.p[kEncoderPrescaler] & ~enc_spec_.prescaler_flags, enc_spec_.prescaler_one);
}

void SwitchCore::advance(SimTime to, std::vector<MotionEvent>& out) {
  collect(
      to, out,
      [this](Motor& m, EventKind k) {
        if (k == EventKind::Deviation) m.errors |= enc_spec_.deviation_flag, m.halted_by = 2, abort_search(m);
        if (k == EventKind::ReferenceDone) m.search.step = SearchStep::Off;
        if (k != EventKind::VelocityReached) m.goal = Goal::Idle, m.trip_t = ramp::kInf;
      },
      [this](Motor& m, const SwitchHit& h) {
        if (m.goal == Goal::Search) search_switch(m, h.input, h.in, h.edge, h.dir);
      },
      [this](const Motor& m) { return next_mech(m); }, [this](Motor& m, std::vector<MotionEvent>& ev) { on_mech(m, ev); });
}

ParamWrite SwitchCore::set_param(int motor, int param, std::int32_t value) {
  Motor& m = at(motor);
  stall_input(m, param);
  if (ParamWrite r{}; cool_param(m, param, value, r)) return r;
  switch (param) {
    case kApTargetPosition: move_absolute(motor, value); return ParamWrite::Ok;
    case kApActualPosition:  // shifts the register; a move in progress still goes to its target
      m.rm.shift(static_cast<std::int64_t>(value) - m.rm.xactual(now_));
      if (m.goal == Goal::Position) replan(m);
      return ParamWrite::Ok;
    case kApTargetSpeed:
      if (!in_range(param, value)) return ParamWrite::OutOfRange;
      rotate(motor, value);
      return ParamWrite::Ok;
    case kApActualSpeed: case kApPositionReached: case kHomeState: case kRightSwitchState:
    case kLeftSwitchState: case kRfsDistance: case kErrorFlags:
      return ParamWrite::ReadOnly;
    case kApRelativePositioningOption:  // read by the next MVP REL (core_skeleton.hpp): no re-plan
      if (!in_range(param, value)) return ParamWrite::OutOfRange;
      m.p[kApRelativePositioningOption] = value;
      return ParamWrite::Ok;
    case kEncoderPosition:  // the count becomes the value where the shaft is
      if (!enc_spec_.present) break;
      if (!in_range(param, value)) return ParamWrite::OutOfRange;
      m.p[kEncoderPosition] = value;
      m.enc.set(shaft_at(m), value);
      shaft_changed(m, false);
      return ParamWrite::Ok;
    case kEncoderPrescaler:
      if (!enc_spec_.present || enc_spec_.prescaler_one <= 0) break;
      if (!in_range(param, value)) return ParamWrite::OutOfRange;
      m.p[kEncoderPrescaler] = value;
      set_prescaler(m);
      shaft_changed(m, false);
      return ParamWrite::Ok;
    case kRfsMode: {
      SearchMode sm;
      if (!in_range(param, value) || !decode(value, sm)) return ParamWrite::OutOfRange;
      m.p[kRfsMode] = value;  // read at the next RFS START
      return ParamWrite::Ok;
    }
    default:
      if (cfg_.last_reference != 0 && param == cfg_.last_reference) return ParamWrite::ReadOnly;
      break;
  }
  const ParamWrite r = set_other(m, param, value);
  if (param == kApRunCurrent && r == ParamWrite::Ok && cool_on_) {  // coolStep starts again from it (E71)
    m.cool = coolstep::start(cool_settings(m));
    m.sg.next_valid = false;
  }
  return r;
}

ParamWrite SwitchCore::set_other(Motor& m, int param, std::int32_t value) {
  if (!in_range(param, value)) return ParamWrite::OutOfRange;  // the profile's range (core_skeleton.hpp)
  const std::int32_t before = m.p[static_cast<std::size_t>(param)];
  m.p[static_cast<std::size_t>(param)] = value;
  if (before != value) replan(m);
  return ParamWrite::Ok;
}

std::int32_t SwitchCore::get_param(int motor, int param) {
  Motor& m = at(motor);
  const ramp::State s = m.rm.state(now_);
  if (std::int32_t v = 0; stall_param(m, param, v, now_)) return v;
  if (param == 180 && cool_on_) return actual_current(m);  // coolstep_core.cpp
  switch (param) {
    case kApActualPosition: return ramp::wrap32(m.rm.xactual(now_));
    case kApTargetSpeed: return target_speed(m, s);
    case kApActualSpeed: return units(s.v / vunit(m));
    case kApPositionReached: return target_reached(motor) ? 1 : 0;
    case kHomeState: return home_state(m) ? 1 : 0;
    case kRightSwitchState: return closed(m, 1) ? 1 : 0;
    case kLeftSwitchState: return closed(m, 0) ? 1 : 0;
    case kErrorFlags: {
      const std::int32_t e = m.errors;
      if (enc_spec_.flags_clear_on_read) m.errors = 0;
      return e;
    }
    case kEncoderPosition: return enc_spec_.present ? ramp::wrap32(encoder(m)) : m.p[kEncoderPosition];
    default: return m.p[static_cast<std::size_t>(param)];
  }
}

std::int32_t SwitchCore::target_speed(const Motor& m, const ramp::State&) const {
  return m.goal == Goal::Velocity ? m.vt : 0;
}

std::int32_t SwitchCore::units(double v) { return static_cast<std::int32_t>(std::trunc(v + (v > 0 ? 1e-9 : -1e-9))); }

void SwitchCore::move_absolute(int motor, std::int32_t target) {
  Motor& m = at(motor);
  m.p[kApTargetPosition] = target;
  m.errors = 0;  // "cleared with the next movement command" (TMCM-351 manual, 207)
  m.halted_by = 0;
  set_goal(m, Goal::Position);
  replan(m, 1, true);
}

void SwitchCore::rotate(int motor, std::int32_t velocity) {
  Motor& m = at(motor);
  m.vt = std::clamp(velocity, -max_speed(), max_speed());  // the chip's register holds no more
  m.errors = 0;
  m.halted_by = 0;
  set_goal(m, Goal::Velocity);
  replan(m, 1, true);
}

void SwitchCore::stop(int motor) {
  Motor& m = at(motor);
  m.errors = 0;
  m.halted_by = 0;
  if (m.goal == Goal::Idle && m.rm.at_rest(now_)) return;
  m.vt = 0;
  set_goal(m, Goal::Velocity);
  replan(m, 1, true);
}

std::int32_t SwitchCore::reference_search(int motor, RfsAction action) {
  Motor& m = at(motor);
  switch (action) {
    case RfsAction::Start:
      m.errors = 0;
      m.halted_by = 0;
      start_search(m);
      return 0;
    case RfsAction::Stop:
      if (m.search.step != SearchStep::Off) stop(motor);
      return 0;
    case RfsAction::Status: return m.search.step != SearchStep::Off ? 1 : 0;
  }
  return 0;
}

bool SwitchCore::reference_done(int motor) const {
  return motors_[static_cast<std::size_t>(motor)].search.step == SearchStep::Off;
}

void SwitchCore::set_switch(int motor, SwitchInput input, bool active) {
  Motor& m = at(motor);
  const int k = static_cast<int>(input);
  const bool was = closed(m, k);
  const auto bit = static_cast<std::uint8_t>(1u << k);
  m.timed = static_cast<std::uint8_t>(active ? m.timed | bit : m.timed & ~bit);
  if (closed(m, k) == was) return;
  if (m.goal == Goal::Search)  // a timed switch has no place: its edge is where the motor is
    search_switch(m, k, closed(m, k), m.rm.xactual(now_), 0);
  else if (active && (m.goal == Goal::Position || m.goal == Goal::Velocity))
    replan(m);  // the trip scan stops the motor at once if it moves toward the switch
}

void SwitchCore::encoder_slip(int motor, std::int32_t counts) {
  Motor& m = at(motor);
  m.shaft.slip(counts);
  shaft_changed(m, true);
}

void SwitchCore::shaft_changed(Motor& m, bool stop_at_rest) {
  if (!deviation_on(m)) return;
  if (m.goal != Goal::Idle) return replan(m);
  if (!stop_at_rest || !m.rm.at_rest(now_)) return;
  const std::int64_t d = deviation(m).at(m.rm.xactual(now_));
  if (d <= m.p[kMaxDeviation] && d >= -m.p[kMaxDeviation]) return;
  Builder b = m.rm.restart(now_);
  b.stop_hard();
  b.event(EventKind::Deviation);
  b.finish_rest();
}

bool SwitchCore::closed(const Motor& m, int input) const {
  if (input == kRefInput) return closed(m, 0) || closed(m, 2);
  return ((m.timed >> input) & 1) || m.rm.zones[static_cast<std::size_t>(input)].in;
}

void SwitchCore::plan_position(Motor& m, Builder& b, const Limits& lim) const {
  b.plan_position(lim, static_cast<double>(m.p[kApTargetPosition] - m.rm.base));
}

void SwitchCore::replan(Motor& m, double vscale, bool by_command) {
  if (m.goal == Goal::Search) return search_step(m, false, vscale);
  if (m.trip_t != ramp::kInf && m.rm.secs(now_) >= m.trip_t && m.goal != Goal::Idle)
    m.goal = Goal::Halt;  // the switch was hit: what is left is its stop
  m.trip_t = ramp::kInf;
  if (m.goal == Goal::Idle) return;
  const Limits lim = ramp_limits(m);
  Builder b = restart(m, vscale);
  switch (m.goal) {
    case Goal::Position: plan_position(m, b, lim); break;
    case Goal::Velocity: b.plan_velocity(lim, m.vt * vunit(m)); break;
    case Goal::Halt: return switch_stop(m, b, lim);
    default: break;
  }
  if (!by_command && m.goal == Goal::Velocity && m.vt != 0) m.rm.drop_repeated_velocity_reached();
  // An arrival within the nanosecond after a whole microsecond is reported at that microsecond:
  // there the motor must read the target, not the step before it (at a stop speed VSTOP or 130 of
  // a few thousand pps the last nanosecond is more than the step tolerance).
  m.rm.rest_on_grid();
  scan_trips(m, lim);
  scan_stops(m, lim);
  scan_deviation(m);
}

// A limit switch stops the motor with the ramp (soft-stop flag 1) or at once (0).
void SwitchCore::switch_stop(Motor& m, Builder& b, const Limits& lim) {
  if (m.p[static_cast<std::size_t>(cfg_.soft_stop)])
    b.stop_ramp(lim);
  else
    b.stop_hard();
  b.event(EventKind::Stopped);
  b.finish_rest();
}

// The first instant the plan moves toward a closed limit switch or reaches a placed one whose
// stop function is on (12, 13 = 0): there the plan is cut and the stop appended.
void SwitchCore::scan_trips(Motor& m, const Limits& lim) {
  if (!cfg_.stop_switches) return;
  const bool left_on = m.p[kLeftStopDisable] == 0, right_on = m.p[kRightStopDisable] == 0;
  if (!left_on && !right_on) return;
  for (const auto& seg : m.rm.plan.segs) {
    if (seg.dir == 0) continue;
    const int input = seg.dir < 0 ? 0 : 1;
    if (!(seg.dir < 0 ? left_on : right_on)) continue;
    double dt = (m.timed >> input) & 1 ? 0.0 : m.rm.entry(seg, input);
    if (dt < 0) continue;
    return stop_at(m, seg.t0 + dt, lim);
  }
}

void SwitchCore::stop_at(Motor& m, double t, const Limits& lim) {
  m.trip_t = t;
  Builder b(m.rm.plan, {}, 0);
  b.truncate(t);
  switch_stop(m, b, lim);
  m.rm.rest_on_grid();
}

// The first step of the plan at which |XACTUAL - 209| exceeds 212: there the motor stops at once
// with a deviation event (manuals: "the motor will be stopped"; docs/motion.md). The shaft is
// taken to stay as it is now (following, or held); each change of that (a contact, a release, a
// load) re-plans, and with it this scan (stall_core.cpp). A shaft held at a hard stop or at a range
// is released where the plan turns away from it: the scan ends there.
void SwitchCore::scan_deviation(Motor& m) {
  if (!deviation_on(m)) return;
  const shaft::Deviation dev = deviation(m);
  for (const auto& seg : m.rm.plan.segs) {
    if (seg.dir == 0) continue;
    if (m.shaft.held && m.sg.block == -seg.dir) return;
    const auto x = dev.trip(m.rm.base + ramp::step_of(seg.x0, seg.dir), seg.dir, m.p[kMaxDeviation]);
    if (!x) continue;
    const double dt = ramp::crossing(seg, static_cast<double>(*x - m.rm.base));
    if (dt < 0) continue;
    Builder b(m.rm.plan, {}, 0);
    b.truncate(seg.t0 + dt);
    b.stop_hard();
    b.event(EventKind::Deviation);
    b.finish_rest();
    m.rm.rest_on_grid();
    return;
  }
}

// ---------------------------------------------------------------- reference search

bool SwitchCore::decode(std::int32_t value, SearchMode& out) const {
  out.mode = value & 63;
  out.other = (value & 64) != 0;
  out.invert = (value & 128) != 0;
  if (cfg_.null_channel && (out.mode == 9 || out.mode == 10)) return value == out.mode;  // no +64, +128
  if (value < 0 || value > 255 || out.mode < 1 || out.mode > 8) return false;
  if (!cfg_.other_switch) return !out.other;  // TMC429 modules: +128 with any mode, no +64
  return !(out.other && out.mode > 4) && !(out.invert && out.mode < 5);
}

// 194 = 0: the maximum positioning speed; 195 = 0: a quarter of it (TMCM-1110 manual, 5.3).
std::int32_t SwitchCore::search_speed(const Motor& m) const {
  return m.p[kRfsSpeed] ? m.p[kRfsSpeed] : m.p[kApMaxPositioningSpeed];
}
std::int32_t SwitchCore::switch_speed(const Motor& m) const {
  return m.p[kRfsSwitchSpeed] ? m.p[kRfsSwitchSpeed] : m.p[kApMaxPositioningSpeed] / 4;
}

// Whether the searched switch is closed (mode + 128: the home switch reads inverted).
bool SwitchCore::search_closed(const Motor& m, int input) const {
  if (input == kNullInput) return false;  // no null channel is modelled: never met
  if (input == kRefInput) return closed(m, 0) || search_closed(m, 2);
  return closed(m, input) != (input == 2 && m.search.m.invert);
}

void SwitchCore::start_search(Motor& m) {
  Search& s = m.search;
  s = Search{};
  if (!decode(m.p[kRfsMode], s.m)) s.m = SearchMode{};
  const int mode = s.m.mode;
  const int near = s.m.other ? 1 : 0, toward = s.m.other ? 1 : -1;  // the zero switch, its direction
  s.far = 1 - near;
  s.step = mode == 2 || mode == 3 ? SearchStep::FindFar : SearchStep::Find;
  if (mode <= 4)
    s.input = mode == 3 && cfg_.home_in_series ? kRefInput : near;
  else
    s.input = mode >= 9 ? kNullInput : 2;
  if (mode <= 4)
    s.dir = s.step == SearchStep::FindFar ? -toward : toward;
  else
    s.dir = mode == 6 || mode == 9 || mode == (cfg_.mode7_negative ? 8 : 7) ? 1 : -1;
  s.reverse_at = mode == 5 ? 0 : mode == 6 ? 1 : -1;
  m.goal = Goal::Search;
  m.trip_t = ramp::kInf;
  search_step(m, false);
}

// Starts the current step from the motor's state now. `stop_first`: the step begins at a switch
// just met, so the motor first stops as the soft-stop flag says (hard: at once; soft: the ramp of
// the turn).
void SwitchCore::search_step(Motor& m, bool stop_first, double vscale) {
  Search& s = m.search;
  Builder b = restart(m, vscale);
  if (stop_first && !m.p[static_cast<std::size_t>(cfg_.soft_stop)]) b.stop_hard();
  if (s.step == SearchStep::ToRef) {
    b.plan_position(search_limits(m, switch_speed(m), true), static_cast<double>(-m.rm.base));
    auto& ev = m.rm.plan.events;  // none when the ramp cannot move (an acceleration or the speed 0)
    if (!ev.empty()) ev.back().kind = EventKind::ReferenceDone;  // the arrival ends the search
    m.rm.rest_on_grid();
    return scan_deviation(m);
  }
  // A release toward an end switch that is closed already (a search that started on its switch
  // right at the end switch): the other way (search_switch).
  if (s.step == SearchStep::Release && closed(m, s.dir < 0 ? 0 : 1) && release_blocked(m, s.dir < 0 ? 0 : 1, s.dir) &&
      !closed(m, s.dir < 0 ? 1 : 0))
    s.dir = -s.dir;
  const bool fast = s.step == SearchStep::Find || s.step == SearchStep::FindFar;
  const Limits lim = search_limits(m, fast ? search_speed(m) : switch_speed(m), false);
  b.plan_velocity(lim, s.dir * lim.vmax);
  m.rm.plan.events.clear();  // the search's own stops and speeds are no events of the program
  scan_deviation(m);
  // A switch already as the step awaits it counts at once (e.g. a search started inside it).
  if (s.step == SearchStep::Find && s.reverse_at >= 0 && closed(m, s.reverse_at)) return turn_around(m);
  const int input = s.step == SearchStep::FindFar ? s.far : s.input;
  const bool want = s.step != SearchStep::Release && s.step != SearchStep::Cross;
  if (search_closed(m, input) == want) search_met(m, m.rm.xactual(now_));
}

// Whether end switch `input`, met moving `dir` while releasing the searched switch, blocks that
// way: it lies in the way, and it is not the switch being released.
bool SwitchCore::release_blocked(const Motor& m, int input, int dir) const {
  const int awaited = m.search.input;
  return (input == 0 || input == 1) && input == (dir < 0 ? 0 : 1) && input != awaited && !(awaited == kRefInput && input == 0);
}

// Modes 5 and 6: the end switch on the way turns the search around, once.
void SwitchCore::turn_around(Motor& m) {
  m.search.reverse_at = -1;
  m.search.dir = -m.search.dir;
  search_step(m, true);
}

// A switch closed or opened during the search: `edge` is where (register counts), `dir` the
// motor's direction then (0: at rest, or a timed switch).
void SwitchCore::search_switch(Motor& m, int input, bool now_closed, std::int64_t edge, int dir) {
  Search& s = m.search;
  if (s.step == SearchStep::Off || s.step == SearchStep::ToRef || (dir != 0 && dir != s.dir)) return;
  if (s.step == SearchStep::Find && input == s.reverse_at && now_closed) return turn_around(m);
  const int awaited = s.step == SearchStep::FindFar ? s.far : s.input;
  // A search that started on its switch (an inverted home switch, +128, is active everywhere
  // outside its range) leaves it the way it leaves a switch it hit: back. When an end switch
  // closes on that way first, the switch cannot be left there: the step turns and leaves it the
  // other way, never running through the end switch (docs/motion.md, *Reference search*).
  if (s.step == SearchStep::Release && now_closed && release_blocked(m, input, s.dir)) {
    s.dir = -s.dir;
    return search_step(m, true);
  }
  if (awaited == kRefInput ? input == 1 : input != awaited) return;
  if (input == 2 && s.m.invert) now_closed = !now_closed;
  if (awaited == kRefInput) now_closed = search_closed(m, kRefInput);
  const bool want = s.step != SearchStep::Release && s.step != SearchStep::Cross;
  if (now_closed == want) search_met(m, edge);
}

// The awaited switching happened at `edge`: record it and go on to the next step.
void SwitchCore::search_met(Motor& m, std::int64_t edge) {
  Search& s = m.search;
  switch (s.step) {
    case SearchStep::FindFar:
      s.far_edge = edge;
      s.step = SearchStep::Find;
      s.dir = -s.dir;
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
bool SwitchCore::far_edge(const Motor& m, int input, int dir) const {
  const ramp::Zone& z = m.rm.zones[static_cast<std::size_t>(input)];
  if (!z.placed || (input == 2 && m.search.m.invert)) return false;
  return dir < 0 ? z.lo != INT64_MIN : z.hi != INT64_MAX;
}

// The reference point is the centre of the two switching points (rounded down): the register
// counts from it from now on, 196 holds the distance of the end switch met first (modes 2 and 3),
// the last-reference parameter the reference point's former position, and the motor goes there
// at the switch speed.
void SwitchCore::reference_at(Motor& m, std::int64_t a, std::int64_t b) {
  Search& s = m.search;
  const std::int64_t sum = a + b, ref = sum >= 0 ? sum / 2 : -((1 - sum) / 2);
  if (s.m.mode == 2 || s.m.mode == 3) {
    const std::int64_t d = s.far_edge - ref;
    m.p[kRfsDistance] = static_cast<std::int32_t>(std::min<std::int64_t>(d < 0 ? -d : d, INT32_MAX));
  }
  if (cfg_.last_reference != 0) m.p[static_cast<std::size_t>(cfg_.last_reference)] = ramp::wrap32(ref);
  m.rm.shift(-ref);
  // The register jumps here: the trace and the plot say so (issue 33, 3).
  report_now(static_cast<int>(&m - motors_.data()), MotionEventKind::Rebased, ramp::wrap32(m.rm.xactual(now_))).value =
      ramp::wrap32(ref);
  m.enc.off -= ref;  // the encoder moves with the counter: the deviation stays (docs/errata.md E68)
  m.p[kApTargetPosition] = 0;
  s.step = SearchStep::ToRef;
  search_step(m, true);
}

}  // namespace tmcl::sw
