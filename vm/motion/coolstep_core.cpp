// coolStep on the TMCM modules' cores (the rules in coolstep.hpp; docs/motion.md, "coolStep"):
//   - the actual current 180 (a current scale 0..31): the standby current 7 at rest, the run
//     current 6 while moving, and while coolStep regulates (172 > 0, speed >= 182) the scale the
//     rules of coolstep.hpp make of each load-value measurement;
//   - the load value is measured with the current the driver drives (stall_core.cpp reads it
//     through reading_scale): a lower current reads lower under the same load, as on the chip;
//   - every change of the scale while moving is an event (CurrentChanged: trace, CSV, plot), so
//     between two events the scale is constant and the closed-form stall search stays exact.
// The regulation runs from measurement to measurement along the plan (cool_walk); on a stretch of
// constant speed and load it stops at the first fixed point, so a motor cruising for an hour costs
// a few dozen measurements, not one per fullstep.
#include <algorithm>
#include <cmath>

#include "measure.hpp"
#include "switch_core.hpp"

namespace tmcl::sw {

using ramp::Segment;
using namespace meas;

namespace {

enum CoolParam : int {
  kCsRun = 6,
  kCsStandby = 7,
  kCsSeimin = 168,
  kCsSedn = 169,
  kCsSemax = 170,
  kCsSeup = 171,
  kCsSemin = 172,
  kCsActual = 180,
  kCsThresholdSpeed = 182,
};

// The most measurements one search walks before it hands back (an event that changes nothing):
// bounds the work of a long ramp whose readings never change the scale.
constexpr int kSearchCap = 4096;

}  // namespace

// The model applies where the module has coolStep besides its load measurement: its profile lists
// the lower threshold 172 (generic: the module the core models stands in). Elsewhere 180 is what
// the profile stores.
void SwitchCore::reset_cool(const Profile& profile) {
  // On stallGuard2's readings (TMCM modules) and on StallGuard4's (TMC2300: its datasheet's
  // CoolStep compares SG_RESULT with the same thresholds; errata E73), in a core that holds
  // coolStep's settings. stallGuard 1 has no coolStep.
  cool_on_ = (guard_ == stall::Guard::SG2 || guard_ == stall::Guard::SG4) && owns(kCsSemin) &&
             (profile.any_parameter || profile.axis_param(kCsSemin) != nullptr);
  for (auto& m : motors_) m.cool = coolstep::start(cool_settings(m));
}

// A current (6, 7: 0..255 on the TMCM modules) as a current scale 0..31 (TMCM-1110 manual 5.2:
// "adjusted in 32 steps"), as the load value's model takes it.
int SwitchCore::scale_of(std::int32_t current) const {
  return static_cast<int>(std::clamp<std::int64_t>(std::int64_t{current} * 32 / current_steps_, 0, 31));
}

coolstep::Settings SwitchCore::cool_settings(const Motor& m) const {
  return {scale_of(m.p[kCsRun]), m.p[kCsSeimin], m.p[kCsSedn], m.p[kCsSemax], m.p[kCsSeup], m.p[kCsSemin]};
}

// Regulation may change the scale: coolStep is on, or the scale is not yet back at the run current.
bool SwitchCore::cool_active(const Motor& m) const {
  if (!cool_on_) return false;
  const coolstep::Settings s = cool_settings(m);
  return coolstep::enabled(s) || m.cool != coolstep::start(s);
}

// coolStep regulates at `pps` (a measurement's speed): the driver measures (StallGuard4: in
// StealthChop only, E73; stallGuard2: not in StealthChop, E78), 172 > 0 and the speed at or above 182 (the stepRocker's open firmware
// switches it off below 182, "abs(Velocity) < ThresholdSpeed"; E72).
bool SwitchCore::regulates(const Motor& m, double pps) const {
  return measures_at(m, pps) && coolstep::enabled(cool_settings(m)) && pps + 1e-9 >= m.p[kCsThresholdSpeed] * vunit(m);
}

// The current scale the load value is measured with: the regulated one (equal to the run
// current's whenever coolStep does not regulate; every change is an event).
int SwitchCore::reading_scale(const Motor& m) const { return cool_on_ ? m.cool.cs : scale_of(m.p[kCsRun]); }

std::int32_t SwitchCore::actual_current(const Motor& m) const {
  if (m.rm.at_rest(now_)) return scale_of(m.p[kCsStandby]);
  return m.cool.cs;
}

// The settings coolStep reads besides the run current (a write first brings it up to now).
bool SwitchCore::cool_input(int param) {
  switch (param) {
    case kCsStandby: case kCsSeimin: case kCsSedn: case kCsSemax: case kCsSeup: case kCsSemin: case kCsThresholdSpeed:
      return true;
    default: return false;
  }
}

// Writes of the parameters coolStep reads. They are stored without a re-plan (they do not change
// the ramp); the regulation up to now has run with the old values (stall_input). A new run current
// starts the regulation again from it (E71). False: not one of them, or no coolStep here.
bool SwitchCore::cool_param(Motor& m, int param, std::int32_t value, ParamWrite& result) {
  if (!cool_on_) return false;
  if (param == kCsActual) {
    result = ParamWrite::ReadOnly;
    return true;
  }
  if (!cool_input(param)) return false;  // 6: the caller stores it and re-plans, then restarts the regulation
  if (!in_range(param, value)) {
    result = ParamWrite::OutOfRange;
    return true;
  }
  m.p[static_cast<std::size_t>(param)] = value;
  m.sg.next_valid = false;
  result = ParamWrite::Ok;
  return true;
}

// Walks the measurements in (s_lo, s_hi] of the plan (plan seconds; s_hi may be infinite), applying
// each to w.st: a measurement at a speed where coolStep regulates reads with the scale w.st.cs and
// then steps it (coolstep::measure); one where it does not, and the start of a rest, bring the
// scale back to the run current (E71). `search`: stop at the first change of the scale, or after
// kSearchCap measurements, and say where (w.stop).
void SwitchCore::cool_walk(const Motor& m, double s_lo, double s_hi, bool search, CoolWalk& w) const {
  const coolstep::Settings set = cool_settings(m);
  const coolstep::State rest = coolstep::start(set);
  const auto& segs = m.rm.plan.segs;
  const double F = fullstep(m), P = period(m), cbase = static_cast<double>(m.rm.base + m.rm.phys);
  const double vmin = stall::kMinFullstepRate * F;
  const bool const_load = m.shaft.held || m.sg.zones.empty();
  const bool meas = measuring(m);
  int walked = 0;
  // Applies the state `next` at plan instant t; true when the search stops there.
  auto apply = [&](const coolstep::State& next, double t) {
    const bool changed = next.cs != w.st.cs;
    w.st = next;
    if (search && (changed || ++walked >= kSearchCap)) {
      w.stop = t;
      return true;
    }
    return false;
  };
  for (std::size_t i = m.rm.plan.find(s_lo); i < segs.size(); ++i) {
    const Segment& seg = segs[i];
    if (seg.t0 > s_hi) break;
    const double end = std::isinf(seg.dur) ? s_hi : std::min(seg.t0 + seg.dur, s_hi);
    if (end < s_lo) continue;
    if (seg.dir == 0) {  // a rest: the standby current, and the run current when it moves again
      if (seg.t0 >= s_lo - kTol && w.st != rest && apply(rest, std::max(seg.t0, s_lo))) return;
      continue;
    }
    double t1 = std::max(seg.t0, s_lo), t2 = end;
    if (!(t1 < t2) || !speed_window(seg, t1, t2, vmin, INFINITY)) continue;
    const bool steady = seg.j == 0 && seg.a0 == 0 && const_load;
    for (double t = first_point(seg, t1, t2, cbase, P); t >= 0;) {
      if (t > s_lo) {
        const double v = speed_at(seg, t);
        const bool on = regulates(m, v);
        coolstep::State next = on ? w.st : rest;
        const int load = m.shaft.held ? 100 : load_at(m, shaft_pos(m, seg, t));
        if (meas && measures_at(m, v)) {  // without one (StallGuard4 outside StealthChop, stallGuard2 in it) 206 holds
          w.value = reading_at(m, v / F, on ? w.st.cs : rest.cs, load);
          w.measured = true;
        }
        if (on) next = coolstep::measure(w.st, set, w.value);
        const bool fixed = next == w.st;
        if (apply(next, t)) return;
        if (steady && fixed) break;  // the same reading from here to the segment's end: nothing changes
      }
      // The next multiple of P the counter passes.
      const double c = cbase + seg.x(t - seg.t0), k = std::round(c / P) * P + seg.dir * P;
      const double dt = ramp::crossing(from(seg, t), k - cbase);
      if (dt < 0 || t + dt > t2 + kTol) break;
      t += dt;
    }
  }
}

// The plan instant of the next change of the scale (or of a search cap), -1: none.
double SwitchCore::next_cool(const Motor& m) const {
  if (!cool_active(m)) return -1;
  CoolWalk w{m.cool};
  cool_walk(m, m.rm.secs(m.sg.commit_us) + kTol, ramp::kInf, true, w);  // m.cool is as of the last commit
  return w.stop;
}

}  // namespace tmcl::sw
