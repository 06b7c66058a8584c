// Loads, stalls and lost steps on the TMCM modules' cores (switch_core.hpp; the model's formulas
// in stall.hpp, the whole in docs/motion.md, "Loads, stalls and lost steps"):
//   - the load value 206, measured when the position counter passes a fullstep (every fourth with
//     the filter 173) at a speed the driver measures at, held in between, at rest and below that
//     speed; 208 bit 0 reads 1 while the last measurement was 0;
//   - stop on stall (181 > 0): at the first measurement that reads 0 at a speed >= 181 the motor
//     stops at once and a `stall` event is reported (the VM raises interrupt 15 + motor);
//   - the machine: a hard stop holds the shaft (shaft.hpp) while the counter pushes on into it, a
//     load of 100 % or more holds it where it stands; the counter runs on (steps lost, said once
//     per hold) until the motor stops or turns away from the hard stop.
//   - the other drivers' measurements the profile names (`motion-constant stallguard`): the
//     TMCM-351's stallGuard 1 (206 0..7 rising with the load, stop at 205, at a constant speed
//     only) and the TMC2300's StallGuard4 (206 not shifted by 174, stop at 2·174, in StealthChop
//     only); a stop on stall sets the profile's `stall-flag` in 207 (errata E74-E76).
// Like the rest of the ramp cores it works in closed form: the next stall, contact or release is
// found on the current plan by root solving (at most a few per segment), never by stepping.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "measure.hpp"
#include "switch_core.hpp"
#include "tmcl/params.hpp"

namespace tmcl::sw {

using ramp::Builder;
using ramp::Segment;

namespace {

enum StallParam : int {
  kRunCurrent = 6,
  kPwmThreshold = 186,    // TMC5160: StealthChop below this speed while 187 > 0 (E78)
  kPwmGradient = 187,     // 0 turns StealthChop off: TMC2300: and with it StallGuard4 (E74); TMC5160: on stallGuard2 (E78)
  kMicrostepResolution = 140,
  kSgFilter = 173,
  kSgThreshold = 174,
  kStopOnStall = 181,
  kLoadValue = 206,
  kDriverFlags = 208,
};
enum MechKind : int { kNone = 0, kStall = 1, kContact = 2, kRelease = 3, kCurrent = 4 };

using namespace meas;  // measure.hpp

}  // namespace

void SwitchCore::reset_stall(const Profile& profile) {
  // The model applies where the module measures the load: its profile says which measurement
  // (`motion-constant stallguard 1|2|4`), or lists stallGuard2's threshold 174 (generic: the
  // module the core models stands in, as for every parameter of the core).
  const Profile* spec = profile.any_parameter ? find_profile(home_) : &profile;
  const bool has174 = profile.any_parameter || profile.axis_param(kSgThreshold) != nullptr;
  guard_ = static_cast<stall::Guard>(spec ? spec->motion_constant("stallguard", has174 ? 2 : 0) : (has174 ? 2 : 0));
  if (guard_ != stall::Guard::SG1 && guard_ != stall::Guard::SG2 && guard_ != stall::Guard::SG4) guard_ = stall::Guard::None;
  sg_on_ = guard_ != stall::Guard::None;
  // 208 bit 0 is stallGuard2's status; a stop on stall sets `stall-flag` in 207 where the manual says.
  flags208_ = guard_ == stall::Guard::SG2 && (profile.any_parameter || profile.axis_param(kDriverFlags) != nullptr);
  stall_flag207_ = spec ? static_cast<std::int32_t>(spec->motion_constant("stall-flag", 0)) : 0;
  // A stallGuard2 module whose profile has the PWM threshold speed 186 switches StealthChop by
  // speed, and stallGuard2 measures nothing in StealthChop (TMC5160; errata E78).
  stealth_by_speed_ = guard_ == stall::Guard::SG2 && spec && spec->axis_param(kPwmThreshold) != nullptr &&
                      spec->axis_param(kPwmGradient) != nullptr;
  const ParamInfo* run = range_row(kRunCurrent);
  current_steps_ = run && run->max > 0 ? run->max + 1 : 256;
  reset_cool(profile);
}

// ---------------------------------------------------------------- the model's inputs

// The current scale 0..31: the run current in 32 steps of its range (TMCM-1110 manual 5.1:
// "0..255 ... adjusted in 32 steps"; the TMC2300's 0..31 are the steps themselves).
int SwitchCore::current_scale(const Motor& m) const {
  return static_cast<int>(std::clamp<std::int64_t>(std::int64_t{m.p[kRunCurrent]} * 32 / current_steps_, 0, 31));
}
double SwitchCore::fullstep(const Motor& m) const { return std::ldexp(1.0, std::clamp(m.p[kMicrostepResolution], 0, 8)); }
// Microsteps between two measurements: one fullstep, four with the filter (173).
double SwitchCore::period(const Motor& m) const { return fullstep(m) * (m.p[kSgFilter] ? 4 : 1); }

// The load on a shaft at `pos` (machine frame): the timed load plus every zone it lies in.
int SwitchCore::load_at(const Motor& m, double pos) const {
  int load = m.sg.load;
  for (const auto& z : m.sg.zones)
    if (pos >= static_cast<double>(z.lo) - kTol && pos < static_cast<double>(z.hi) + 1 - kTol) load += z.percent;
  return load;
}
double SwitchCore::shaft_pos(const Motor& m, const Segment& seg, double t) const {
  if (m.shaft.held) return static_cast<double>(m.shaft.held_at);
  return static_cast<double>(m.rm.base + m.rm.phys + m.shaft.offset) + seg.x(t - seg.t0);
}

bool SwitchCore::stops_on_stall(const Motor& m) const {
  if (!measuring(m)) return false;
  return guard_ == stall::Guard::SG1 ? m.p[kSg1Threshold] > 0 : m.p[kStopOnStall] > 0;
}

// The driver measures: it has a load measurement, and StallGuard4 only in StealthChop (187 > 0).
bool SwitchCore::measuring(const Motor& m) const {
  return sg_on_ && (guard_ != stall::Guard::SG4 || m.p[kPwmGradient] > 0);
}

// The speed (pps) below which the TMC5160 drives in StealthChop and stallGuard2 measures nothing:
// 186 while 187 > 0 ("switched on when the actual velocity is below this value (and parameter
// #187 is greater than zero)", PD57/60-1260 manual 186); 0 elsewhere (errata E78).
double SwitchCore::stealth_below(const Motor& m) const {
  if (!stealth_by_speed_ || m.p[kPwmGradient] <= 0) return 0;
  return m.p[kPwmThreshold] * vunit(m);
}

// The reading at `f` fullsteps/s under `load` %, by the module's measurement (stall.hpp), with
// the current scale the driver drives (reading_at: with the scale `cs`).
int SwitchCore::measure(const Motor& m, double f, int load) const { return reading_at(m, f, reading_scale(m), load); }
int SwitchCore::reading_at(const Motor& m, double f, int cs, int load) const {
  switch (guard_) {
    case stall::Guard::SG1: return stall::reading1(load);
    case stall::Guard::SG4: return stall::reading4(f, cs, load);
    default: return stall::reading(f, cs, load, m.p[kSgThreshold]);
  }
}

// The fullstep rate below which a measurement under `load` % means a stall (stallGuard 1: any
// speed or none, the reading does not depend on it).
double SwitchCore::stall_below(const Motor& m, int load) const {
  switch (guard_) {
    case stall::Guard::SG1: return stall::reading1(load) >= m.p[kSg1Threshold] ? INFINITY : 0;
    case stall::Guard::SG4: return stall::stall_below4(reading_scale(m), load, m.p[kSgThreshold]);
    default: return stall::zero_below(reading_scale(m), load, m.p[kSgThreshold]);
  }
}

// The reading a stop on stall leaves in 206: a stall's, even where the measurement shares its
// microsecond with the contact that caused it.
int SwitchCore::stall_reading(const Motor& m, int value) const {
  switch (guard_) {
    case stall::Guard::SG1: return std::max(value, m.p[kSg1Threshold]);
    case stall::Guard::SG4: return std::min(value, stall::stall_level4(m.p[kSgThreshold]));
    default: return 0;
  }
}

// ---------------------------------------------------------------- reading the load value

bool SwitchCore::last_reading(const Motor& m, int& value, SimTime at) const {
  if (!measuring(m)) return false;
  const auto& segs = m.rm.plan.segs;
  const double s_now = m.rm.secs(at) + kTol, s_lo = m.rm.secs(m.sg.commit_us) + kTol;
  const double cbase = static_cast<double>(m.rm.base + m.rm.phys), F = fullstep(m);
  const double vmin = std::max(stall::kMinFullstepRate * F, stealth_below(m));  // none in StealthChop (E78)
  for (std::size_t i = m.rm.plan.find(s_now - kTol) + 1; i-- > 0;) {
    const Segment& seg = segs[i];
    const double end = std::isinf(seg.dur) ? s_now : std::min(seg.t0 + seg.dur, s_now);
    if (end <= s_lo) break;  // and every segment before it
    if (seg.dir == 0 || !steady_enough(seg)) continue;
    double t1 = std::max(seg.t0, s_lo), t2 = end;
    if (!(t1 < t2) || !speed_window(seg, t1, t2, vmin, INFINITY)) continue;
    const double t = last_point(seg, t1, t2, cbase, period(m));
    if (t < 0 || t <= s_lo) continue;
    const int load = m.shaft.held ? 100 : load_at(m, shaft_pos(m, seg, t));
    value = measure(m, speed_at(seg, t) / F, load);
    return true;
  }
  return false;
}

void SwitchCore::commit(Motor& m) {
  if (cool_active(m)) {  // coolStep: the measurements one by one, each with the current it met
    CoolWalk w{m.cool};
    cool_walk(m, m.rm.secs(m.sg.commit_us) + kTol, m.rm.secs(now_) + kTol, false, w);
    m.cool = w.st;
    if (w.measured) m.sg.value = w.value, m.sg.measured = true;
  } else if (int v = 0; last_reading(m, v, now_)) {
    m.sg.value = v, m.sg.measured = true;
  }
  m.sg.commit_us = now_;
  m.sg.next_valid = false;
}

Builder SwitchCore::restart(Motor& m, double vscale) {
  commit(m);
  return m.rm.restart(now_, vscale);
}

void SwitchCore::stall_input(Motor& m, int param) {
  switch (param) {
    case kRunCurrent: case kMicrostepResolution: case kSgFilter: case kSgThreshold: case kStopOnStall:
    case kPwmThreshold: case kPwmGradient: case kSg1Threshold:
      commit(m);
      break;
    default:
      if (cool_input(param)) commit(m);  // coolStep's settings (coolstep_core.cpp)
      break;
  }
}

bool SwitchCore::stall_param(const Motor& m, int param, std::int32_t& value, SimTime at) const {
  if (!sg_on_ || (param != kLoadValue && param != kDriverFlags)) return false;
  int v = m.sg.value;
  const bool measured = last_reading(m, v, at) || m.sg.measured;
  if (param == kLoadValue) {
    value = measured ? v : m.p[kLoadValue];
    return true;
  }
  if (!flags208_) return false;
  value = measured && v == 0 ? 1 : 0;  // bit 0: stallGuard2 status
  return true;
}

// ---------------------------------------------------------------- the machine

bool SwitchCore::place_hard_stop(int motor, SwitchInput side, std::int64_t position) {
  Motor& m = at(motor);
  const int k = side == SwitchInput::StopRight ? 1 : 0;
  m.sg.hard[k] = true;
  m.sg.hard_at[k] = position;
  m.sg.next_valid = false;
  return true;
}

bool SwitchCore::set_load(int motor, int percent) {
  Motor& m = at(motor);
  commit(m);
  m.sg.load = percent;
  if (m.sg.block == 2 && percent < 100) {  // the load lets go (a range it stands in may hold it again)
    release_shaft(m);
    m.sg.block = 0;
    shaft_changed(m, false);  // the deviation stop the hold had planned goes with it
  }
  return true;
}

bool SwitchCore::place_load(int motor, std::int64_t lo, std::int64_t hi, int percent) {
  Motor& m = at(motor);
  commit(m);
  m.sg.zones.push_back({lo, hi, percent});
  return true;
}

// ---------------------------------------------------------------- events

SimTime SwitchCore::next_event() const {
  SimTime t = RampCore::next_event();
  for (const auto& m : motors_) t = std::min(t, next_mech(m));
  return t;
}

// Where a segment moving from t1 (not held) meets what holds its shaft: a hard stop ahead, a zone
// whose load reaches 100 % ahead, or a load of 100 % or more where it is. -1: nothing before t2.
// `why`: the block it makes: 2 for a timed load of 100 % or more, which holds the shaft whichever
// way the motor turns (a brake); seg.dir for a hard stop and for a range of positions, which
// resist the shaft moving into them only: turning away lets it follow again (docs/motion.md).
double SwitchCore::contact(const Motor& m, const Segment& seg, double t1, double t2, int& why) const {
  const double pos = shaft_pos(m, seg, t1), shift = static_cast<double>(m.rm.base + m.rm.phys + m.shaft.offset);
  const Segment s = from(seg, t1);
  double best = -1;
  auto take = [&](double edge, int kind) {
    double dt = seg.dir * (pos - edge) >= -kTol ? 0 : ramp::crossing(s, edge - shift);
    if (dt < 0 || t1 + dt > t2) return;
    if (best < 0 || t1 + dt < best) best = t1 + dt, why = kind;
  };
  if (m.sg.load >= 100) {
    why = 2;
    return t1;
  }
  if (load_at(m, pos) >= 100 && load_at(m, pos + seg.dir) >= 100) {  // in a range, moving on into it
    why = seg.dir;
    return t1;
  }
  const int side = seg.dir > 0 ? 1 : 0;
  if (m.sg.hard[side]) take(static_cast<double>(m.sg.hard_at[side]), seg.dir);
  for (const auto& z : m.sg.zones) {
    const double edge = seg.dir > 0 ? static_cast<double>(z.lo) : static_cast<double>(z.hi);
    if (seg.dir * (edge - pos) > 0 && load_at(m, edge) >= 100) take(edge, seg.dir);
  }
  return best;
}

// The first measurement in [t1, t2] of a moving segment that means a stall (stallGuard2: it reads 0)
// at a speed >= 181 (stallGuard 1: at any speed it measures at); -1 none.
double SwitchCore::first_stall(const Motor& m, const Segment& seg, double t1, double t2) const {
  const double F = fullstep(m), cbase = static_cast<double>(m.rm.base + m.rm.phys);
  if (!steady_enough(seg)) return -1;
  const double v181 = guard_ == stall::Guard::SG1 ? 0 : m.p[kStopOnStall] * vunit(m);  // stallGuard 1 has no 181
  const double vlo = std::max({v181, stall::kMinFullstepRate * F, stealth_below(m)});  // E78: none in StealthChop
  // Pieces of constant load: split at the zones' edges on the way (none held: the blocked rotor).
  std::vector<double> cuts{t1};
  if (!m.shaft.held) {
    const double shift = static_cast<double>(m.rm.base + m.rm.phys + m.shaft.offset);
    const Segment s = from(seg, t1);
    for (const auto& z : m.sg.zones)
      for (double edge : {static_cast<double>(z.lo) - kTol, static_cast<double>(z.hi) + 1 - kTol}) {
        const double dt = ramp::crossing(s, edge - shift);
        if (dt > 0 && t1 + dt < t2) cuts.push_back(t1 + dt);
      }
    std::sort(cuts.begin(), cuts.end());
  }
  cuts.push_back(t2);
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    double a = cuts[i], b = cuts[i + 1];
    const double mid = std::isinf(b) ? a : (a + b) / 2;
    const int load = m.shaft.held ? 100 : load_at(m, shaft_pos(m, seg, mid));
    const double vhi = stall_below(m, load) * F;
    if (!speed_window(seg, a, b, vlo, vhi)) continue;
    const double t = first_point(seg, a, b, cbase, period(m));
    if (t >= 0) return t;
  }
  return -1;
}

// The next stall, contact or release under the current plan (cached until the plan or an input
// changes).
SimTime SwitchCore::next_mech(const Motor& m) const {
  const stall::Axis& g = m.sg;
  if (g.next_valid && g.next_gen == m.rm.gen) return g.next_at;
  g.next_valid = true, g.next_gen = m.rm.gen, g.next_at = kNever, g.next_kind = kNone;
  const bool stops = stops_on_stall(m);
  // coolStep's next change comes first at the same instant: the stall search after it uses its scale.
  const double cool_t = next_cool(m);
  auto found = [&](double t, int kind) {
    if (cool_t >= 0 && cool_t <= t) t = cool_t, kind = kCurrent;
    g.next_at = m.rm.origin + ramp::ceil_us(t), g.next_kind = kind;
    return g.next_at;
  };
  const SimTime none = cool_t >= 0 ? found(cool_t, kCurrent) : kNever;
  if (!stops && !g.has_machine() && g.block == 0) return none;
  const auto& segs = m.rm.plan.segs;
  const double s_now = m.rm.secs(now_);
  for (std::size_t i = m.rm.plan.find(s_now); i < segs.size(); ++i) {
    const Segment& seg = segs[i];
    if (seg.dir == 0) continue;
    const double t1 = std::max(seg.t0, s_now), t2 = std::isinf(seg.dur) ? ramp::kInf : seg.t0 + seg.dur;
    if (m.shaft.held) {
      if (g.block != 2 && seg.dir == -g.block) return found(t1, kRelease);
      if (stops)
        if (double t = first_stall(m, seg, t1, t2); t >= 0) return found(t, kStall);
      continue;
    }
    int why = 0;
    const double tc = contact(m, seg, t1, t2, why);
    if (stops)
      if (double t = first_stall(m, seg, t1, tc >= 0 ? tc : t2); t >= 0) return found(t, kStall);
    if (tc >= 0) {
      g.next_kind = kContact;
      return found(tc, kContact);
    }
  }
  return none;
}

void SwitchCore::on_mech(Motor& m, std::vector<MotionEvent>& out) {
  const int kind = m.sg.next_kind;
  const auto motor = static_cast<std::uint8_t>(&m - motors_.data());
  const int cs_before = m.cool.cs;
  commit(m);
  switch (kind) {
    case kCurrent:  // coolStep stepped the current (or its search paused): shown while moving
      if (m.cool.cs != cs_before && !m.rm.at_rest(now_)) {
        MotionEvent ev{now_, motor, MotionEventKind::CurrentChanged, ramp::wrap32(m.rm.xactual(now_))};
        ev.value = actual_current(m);
        out.push_back(ev);
      }
      break;
    case kStall: {  // stop on stall: at once, the target kept; the VM raises 15 + motor
      // This measurement, taken now (it may share its microsecond with a contact, or with the
      // load change that caused it).
      const double f = std::fabs(m.rm.state(now_).v) / fullstep(m);
      const int load = m.shaft.held ? 100 : load_at(m, static_cast<double>(shaft_at(m)));
      Builder b = restart(m);
      m.sg.value = stall_reading(m, measure(m, f, load)), m.sg.measured = true;
      m.errors |= stall_flag207_;  // 207: "stopped due to motor stall" where the manual has it
      m.halted_by = 1;
      b.stop_hard();
      b.finish_rest();
      m.rm.plan.events.clear();
      set_goal(m, Goal::Idle);
      MotionEvent ev{now_, motor, MotionEventKind::Stall, ramp::wrap32(m.rm.xactual(now_))};
      ev.value = m.sg.value;
      out.push_back(ev);
      break;
    }
    case kContact: {
      const Segment& seg = m.rm.plan.segs[m.rm.plan.find(m.rm.secs(now_))];
      int why = 0;
      (void)contact(m, seg, m.rm.secs(now_), m.rm.secs(now_), why);
      hold_shaft(m);
      m.sg.block = why == 0 ? seg.dir : why;
      m.sg.next_valid = false;
      {  // the contact, always (issue 41): what the shaft met, before what follows from it
        MotionEvent ev{now_, motor, MotionEventKind::Contact, ramp::wrap32(m.rm.xactual(now_))};
        const int load = load_at(m, static_cast<double>(m.shaft.held_at));
        if (load >= 100) ev.value = load;  // a timed load or a load range
        else ev.input = seg.dir > 0 ? SwitchInput::StopRight : SwitchInput::StopLeft;
        out.push_back(ev);
      }
      // The counter now parts from the shaft: the deviation stop (212) is planned where it passes
      // 212, mid-plan as at a plan's start (switch_core.cpp, scan_deviation).
      shaft_changed(m, false);
      // Steps are lost from here; said once, unless stop on stall stops the motor at the next
      // measurement (within a measurement period: stallGuard 1 waits for a constant speed).
      const bool stops_soon = next_mech(m) != kNever && m.sg.next_kind == kStall &&
                              static_cast<double>(std::abs(m.rm.xactual(m.sg.next_at) - m.rm.xactual(now_))) <= period(m) + 1;
      if (!stops_soon) {
        MotionEvent ev{now_, motor, MotionEventKind::StepsLost, ramp::wrap32(m.rm.xactual(now_))};
        // Stop on stall is on, yet StealthChop keeps stallGuard2 from measuring here (E78): the
        // program relies on a stall the module cannot see (the VM notes it).
        const double v = std::fabs(m.rm.state(now_).v);
        if (stealth_below(m) > 0 && v < stealth_below(m) && m.p[kStopOnStall] > 0) ev.value = kStepsLostStallUnseen;
        out.push_back(ev);
      }
      break;
    }
    case kRelease:
      release_shaft(m);
      m.sg.block = 0;
      shaft_changed(m, false);  // following again: the deviation changes as the counter moves
      break;
    default: break;
  }
  m.sg.next_valid = false;
}

}  // namespace tmcl::sw
