// One motor's current plan in simulated time, shared by the ramp-generator cores: the plan's
// origin (an integer microsecond), the integer position its doubles are relative to, and which of
// its events have been reported. Time rounding lives here: a plan instant t (seconds, exact) is
// reported at the first whole microsecond >= t (1 ns of floating-point noise tolerated).
// Also the switches placed at positions (MotionCore::place_switch) and the instant the plan next
// closes or opens one of them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>

#include "core_skeleton.hpp"
#include "ramp.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"
#include "tmcl/profile.hpp"

namespace tmcl::ramp {

inline SimTime ceil_us(double t) {
  double us = std::ceil(t * 1e6 - 1e-3);
  if (!(us < 9e18)) return kNever;
  return static_cast<SimTime>(us);
}

inline std::int32_t wrap32(std::int64_t v) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(v)));
}

// A switch placed at positions: closed while the physical position (XACTUAL + RampMotor::phys)
// lies in [lo, hi]. The position is the whole step XACTUAL, so moving + the switch closes when x
// reaches lo and opens when it reaches hi + 1; moving - it closes at hi and opens at lo - 1.
struct Zone {
  bool placed = false;
  bool in = false;  // closed now, as last reported
  std::int64_t lo = 0, hi = 0;
  bool contains(std::int64_t p) const { return placed && p >= lo && p <= hi; }
};

// The next closing or opening of a placed switch.
struct SwitchHit {
  SimTime at = kNever;
  int input = 0;              // SwitchInput
  bool in = false;            // closed after it
  std::int64_t position = 0;  // XACTUAL then
  std::int64_t edge = 0;      // the zone's edge it switched at, as XACTUAL (register) counts
  int dir = 0;                // the motor's direction then (0: at rest)
};

struct RampMotor {
  Plan plan;
  SimTime origin = 0;
  std::int64_t base = 0;  // plan positions are relative to this step
  std::size_t next = 0;   // next plan event to report
  std::int64_t phys = 0;  // physical position - XACTUAL: moved by SAP 1 and reference searches
  std::array<Zone, 3> zones{};  // by SwitchInput
  bool has_zones = false;
  std::uint32_t gen = 0;  // counts changes of the plan and the register (restart, shift): keys caches

  RampMotor() { plan.segs.push_back({0, kInf, 0, 0, 0, 0, 0}), plan.t_rest = 0; }

  double secs(SimTime t) const { return static_cast<double>(t - origin) * 1e-6; }
  State state(SimTime t) const { return plan.at(secs(t)); }
  std::int64_t xactual(SimTime t) const {
    double s = secs(t);
    const Segment& seg = plan.segs[plan.find(s)];
    double dt = std::min(std::max(0.0, s - seg.t0), seg.dur);
    return base + step_of(seg.x(dt), seg.dir);
  }
  SimTime event_time(std::size_t i) const { return origin + ceil_us(plan.events[i].t); }
  SimTime next_event() const { return next < plan.events.size() ? event_time(next) : kNever; }
  bool at_rest(SimTime now) const { return plan.t_rest != kInf && origin + ceil_us(plan.t_rest) <= now; }

  // Starts a new plan at `now` from the state the old one has then; returns the builder. The new
  // base is the current step wrapped to 32 bits, as the chip's position register is. `vscale`
  // multiplies the speed and acceleration there (a chip whose velocity unit changed: tmc429).
  Builder restart(SimTime now, double vscale = 1) {
    double s = secs(now);
    const Segment& seg = plan.segs[plan.find(s)];
    double dt = std::min(std::max(0.0, s - seg.t0), seg.dur);
    State st{0, seg.x(dt), seg.v(dt) * vscale, seg.a(dt) * vscale};
    int dir = seg.dir;
    // How long the motor has rested (the ramp wait counts it), when the old plan has ended.
    const double rested = plan.t_rest != kInf && s >= plan.t_rest ? std::max(0.0, s - plan.rest_at) : -1;
    std::int64_t step = base + step_of(st.x, dir);
    std::int64_t nb = wrap32(step);
    st.x -= static_cast<double>(nb - base);
    base = nb;
    origin = now;
    next = 0;
    plan.clear();
    hit_valid_ = false;
    ++gen;
    Builder b(plan, st, dir);
    if (rested >= 0) b.rested(rested);
    return b;
  }

  // A rest that begins within the tolerance of ceil_us after a whole microsecond begins on it, so
  // that at the microsecond its stop is reported the motor reads at rest (a hard stop jumps).
  void rest_on_grid() {
    if (plan.t_rest == kInf) return;
    const double u = static_cast<double>(ceil_us(plan.t_rest)) * 1e-6;
    if (!(u < plan.t_rest)) return;
    plan.segs.back().t0 = u;
    if (plan.segs.size() > 1) {
      Segment& prev = plan.segs[plan.segs.size() - 2];
      prev.dur = std::max(0.0, u - prev.t0);
    }
    for (auto& e : plan.events) e.t = std::min(e.t, u);
    plan.t_rest = u;
  }

  // A re-plan caused by a parameter or a switch, not by a command, of a motor already cruising at
  // its target speed does not report "velocity reached" again (docs/motion.md, decision 17).
  void drop_repeated_velocity_reached() {
    auto& ev = plan.events;
    if (!ev.empty() && ev.front().t == 0 && ev.front().kind == EventKind::VelocityReached) ev.erase(ev.begin());
  }

  // Shifts the register (SAP 1, a reference search): XACTUAL changes by d, the switches stay.
  void shift(std::int64_t d) {
    base += d;
    phys -= d;
    hit_valid_ = false;
    ++gen;
  }
  void place(int input, std::int64_t lo, std::int64_t hi) {
    zones[static_cast<std::size_t>(input)] = {true, false, lo, hi};  // reported closed by the scan if inside
    has_zones = true;
    hit_valid_ = false;
  }
  // The next switch change at or after `from` under the current plan (cached until the plan, the
  // register or a switch changes).
  const SwitchHit& next_switch(SimTime from) const {
    if (!hit_valid_) {
      hit_ = has_zones ? scan_switches(from) : SwitchHit{};
      hit_valid_ = true;
    }
    return hit_;
  }
  SimTime next_switch_at(SimTime from) const { return has_zones ? next_switch(from).at : kNever; }
  // The reported change happened: the switch is in its new state.
  void switched(const SwitchHit& h) {
    zones[static_cast<std::size_t>(h.input)].in = h.in;
    hit_valid_ = false;
  }
  // Where a segment moving toward a placed switch enters it: 0 when it starts inside, the instant
  // (seconds into the segment) it reaches the entry step, or a negative number when it does not.
  double entry(const Segment& seg, int input) const {
    const Zone& z = zones[static_cast<std::size_t>(input)];
    if (!z.placed || seg.dir == 0) return -1;
    std::int64_t p = base + step_of(seg.x0, seg.dir) + phys;
    if (z.contains(p)) return 0;
    if ((seg.dir > 0 && p > z.hi) || (seg.dir < 0 && p < z.lo)) return -1;
    return crossing(seg, plan_x(seg.dir > 0 ? z.lo : z.hi));
  }

 private:
  mutable SwitchHit hit_;
  mutable bool hit_valid_ = false;

  double plan_x(std::int64_t physical) const { return static_cast<double>(physical - phys - base); }

  // From just after `from`: an instant within ceil_us's nanosecond after it is reported at
  // `from`, so a change there has been reported already and the motor counts as past it.
  SwitchHit scan_switches(SimTime from) const {
    SwitchHit best;
    const double s = secs(from) + 1.01e-9;
    for (std::size_t i = plan.find(s); i < plan.segs.size(); ++i) {
      Segment seg = plan.segs[i];
      const bool first = seg.t0 < s;
      if (first) {  // the part of the segment from `from` on
        double dt = std::min(s - seg.t0, seg.dur);
        seg = {seg.t0 + dt, seg.dur - dt, seg.x(dt), seg.v(dt), seg.a(dt), seg.j, seg.dir};
      }
      const std::int64_t p0 = base + step_of(seg.x0, seg.dir) + phys;
      for (int k = 0; k < 3; ++k) {
        const Zone& z = zones[static_cast<std::size_t>(k)];
        if (!z.placed) continue;
        double t = -1;
        std::int64_t at = 0, edge = 0;
        if (z.contains(p0) != z.in) {  // out of step with the switch where the segment starts
          t = 0, at = p0, edge = p0;
        } else if (seg.dir != 0 && !z.in) {  // entering, at the edge it comes to
          if ((seg.dir > 0 && p0 < z.lo) || (seg.dir < 0 && p0 > z.hi)) {
            edge = at = seg.dir > 0 ? z.lo : z.hi;
            t = crossing(seg, plan_x(at));
          }
        } else if (seg.dir != 0 && (seg.dir > 0 ? z.hi : z.lo) != (seg.dir > 0 ? INT64_MAX : INT64_MIN)) {
          edge = seg.dir > 0 ? z.hi : z.lo;  // leaving: one step past the edge
          at = edge + seg.dir;
          t = crossing(seg, plan_x(at));
        }
        if (t < 0) continue;
        SimTime when = first && t == 0 ? from : origin + ceil_us(seg.t0 + t);
        if (when < best.at) best = {when, k, !z.in, at - phys, edge - phys, seg.dir};
      }
      if (best.at != kNever) return best;
    }
    return best;
  }
};


// What every core built on RampMotor shares beyond the skeleton (core_skeleton.hpp): each
// motor's plan (M has a RampMotor `rm` besides the owned parameters `p`), the next event, the
// position and samples read from the plans, and turning each motor's plan events into
// MotionEvents in time order. A core adds its parameters and commands and reacts to its motors'
// events in collect's hook.
template <class M>
class RampCore : public CoreSkeleton<M> {
 public:
  using CoreSkeleton<M>::CoreSkeleton;

  SimTime next_event() const override {
    SimTime t = this->next_pending();
    for (const auto& m : motors_) t = std::min({t, m.rm.next_event(), m.rm.next_switch_at(now_)});
    return t;
  }
  // Switches at positions: every ramp core reports them; what they stop is the core's.
  bool place_switch(int motor, SwitchInput input, std::int64_t lo, std::int64_t hi) override {
    at(motor).rm.place(static_cast<int>(input), lo, hi);
    return true;
  }
  std::int32_t position(int motor) const override {
    return wrap32(motors_[static_cast<std::size_t>(motor)].rm.xactual(now_));
  }
  // At rest on the target (parameter 0): WAIT POS and parameter 8.
  bool target_reached(int motor) const override {
    const M& m = motors_[static_cast<std::size_t>(motor)];
    return m.rm.at_rest(now_) && wrap32(m.rm.xactual(now_)) == m.p[kApTargetPosition];
  }
  bool reference_done(int) const override { return true; }
  MotionSample sample_at(int motor, SimTime t) const override {
    const M& m = motors_[static_cast<std::size_t>(motor)];
    State s = m.rm.state(t);
    return {m.rm.xactual(t), s.v, s.a};
  }

 protected:
  using CoreSkeleton<M>::motors_;
  using CoreSkeleton<M>::now_;
  using CoreSkeleton<M>::at;

  // Advances to `to` and appends the events on the way, each motor's plan events and switch
  // changes in time order (a switch first at the same microsecond). After each, with now_ at its
  // instant, on_event(motor, kind) or on_switch(motor, hit) runs; either may re-plan the motor.
  // `next_extra(m)` and `on_extra(m, out)`: a third source of events a core adds (stall.hpp: stalls
  // and the shaft meeting a hard stop), after a plan event at the same microsecond.
  template <class OnEvent, class OnSwitch>
  void collect(SimTime to, std::vector<MotionEvent>& out, OnEvent on_event, OnSwitch on_switch) {
    collect(to, out, on_event, on_switch, [](const M&) { return kNever; }, [](M&, std::vector<MotionEvent>&) {});
  }
  template <class OnEvent, class OnSwitch, class NextExtra, class OnExtra>
  void collect(SimTime to, std::vector<MotionEvent>& out, OnEvent on_event, OnSwitch on_switch, NextExtra next_extra,
               OnExtra on_extra) {
    const SimTime from = now_, end = std::max(to, now_);
    std::size_t first = out.size();
    this->take_pending(out);
    for (std::size_t i = 0; i < motors_.size(); ++i) {
      M& m = motors_[i];
      for (;;) {
        const SimTime tp = m.rm.next_event(), ts = m.rm.next_switch_at(now_), tx = next_extra(m);
        if (std::min({tp, ts, tx}) > end) break;
        now_ = std::min({tp, ts, tx});
        if (tx < std::min(tp, ts)) {
          on_extra(m, out);
        } else if (ts <= tp) {
          const SwitchHit h = m.rm.next_switch(now_);
          m.rm.switched(h);
          MotionEvent ev{h.at, static_cast<std::uint8_t>(i), MotionEventKind::SwitchChanged, wrap32(h.position)};
          ev.input = static_cast<SwitchInput>(h.input);
          ev.active = h.in;
          out.push_back(ev);
          on_switch(m, h);
        } else {
          EventKind k = m.rm.plan.events[m.rm.next++].kind;
          out.push_back({tp, static_cast<std::uint8_t>(i), motion_kind(k), wrap32(m.rm.xactual(tp))});
          on_event(m, k);
        }
        this->take_pending(out);
      }
      now_ = from;
    }
    now_ = end;
    if (motors_.size() > 1)
      std::stable_sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
                       [](const MotionEvent& a, const MotionEvent& b) { return a.at < b.at; });
  }
  template <class OnEvent>
  void collect(SimTime to, std::vector<MotionEvent>& out, OnEvent on_event) {
    collect(to, out, on_event, [](M&, const SwitchHit&) {});
  }

  // An instant reference search: the motor stops where it is, that place becomes position 0
  // (and the target), and ReferenceDone is reported by the next advance.
  void zero_here(int motor) {
    M& m = at(motor);
    Builder b = m.rm.restart(now_);
    b.stop_hard();
    b.finish_rest();
    m.rm.plan.events.clear();
    m.rm.shift(-m.rm.xactual(now_));
    m.p[kApTargetPosition] = 0;
    this->report_now(motor, MotionEventKind::ReferenceDone, 0);
  }

  static MotionEventKind motion_kind(EventKind k) {
    switch (k) {
      case EventKind::TargetReached: return MotionEventKind::TargetReached;
      case EventKind::VelocityReached: return MotionEventKind::VelocityReached;
      case EventKind::Stopped: return MotionEventKind::Stopped;
      case EventKind::Deviation: return MotionEventKind::Deviation;
      case EventKind::ReferenceDone: return MotionEventKind::ReferenceDone;
    }
    return MotionEventKind::Stopped;
  }

};

}  // namespace tmcl::ramp
