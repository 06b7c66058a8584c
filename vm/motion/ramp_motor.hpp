// One motor's current plan in simulated time, shared by the ramp-generator cores: the plan's
// origin (an integer microsecond), the integer position its doubles are relative to, and which of
// its events have been reported. Time rounding lives here: a plan instant t (seconds, exact) is
// reported at the first whole microsecond >= t (1 ns of floating-point noise tolerated).
#pragma once

#include <algorithm>
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

struct RampMotor {
  Plan plan;
  SimTime origin = 0;
  std::int64_t base = 0;  // plan positions are relative to this step
  std::size_t next = 0;   // next plan event to report

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
  // base is the current step wrapped to 32 bits, as the chip's position register is.
  Builder restart(SimTime now) {
    double s = secs(now);
    const Segment& seg = plan.segs[plan.find(s)];
    double dt = std::min(std::max(0.0, s - seg.t0), seg.dur);
    State st{0, seg.x(dt), seg.v(dt), seg.a(dt)};
    int dir = seg.dir;
    std::int64_t step = base + step_of(st.x, dir);
    std::int64_t nb = wrap32(step);
    st.x -= static_cast<double>(nb - base);
    base = nb;
    origin = now;
    next = 0;
    plan.clear();
    return Builder(plan, st, dir);
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
    for (const auto& m : motors_) t = std::min(t, m.rm.next_event());
    return t;
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

  // Advances to `to` and appends the events on the way; on_event(motor, kind) runs after each.
  template <class OnEvent>
  void collect(SimTime to, std::vector<MotionEvent>& out, OnEvent on_event) {
    if (to > now_) now_ = to;
    std::size_t first = out.size();
    this->take_pending(out);
    for (std::size_t i = 0; i < motors_.size(); ++i) {
      M& m = motors_[i];
      while (m.rm.next_event() <= now_) {
        SimTime when = m.rm.event_time(m.rm.next);
        EventKind k = m.rm.plan.events[m.rm.next++].kind;
        out.push_back({when, static_cast<std::uint8_t>(i), motion_kind(k), wrap32(m.rm.xactual(when))});
        on_event(m, k);
      }
    }
    if (motors_.size() > 1)
      std::stable_sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
                       [](const MotionEvent& a, const MotionEvent& b) { return a.at < b.at; });
  }

  // An instant reference search: the motor stops where it is, that place becomes position 0
  // (and the target), and ReferenceDone is reported by the next advance.
  void zero_here(int motor) {
    M& m = at(motor);
    Builder b = m.rm.restart(now_);
    b.stop_hard();
    b.finish_rest();
    m.rm.plan.events.clear();
    m.rm.base -= m.rm.xactual(now_);
    m.p[kApTargetPosition] = 0;
    this->report_now(motor, MotionEventKind::ReferenceDone, 0);
  }

  static MotionEventKind motion_kind(EventKind k) {
    switch (k) {
      case EventKind::TargetReached: return MotionEventKind::TargetReached;
      case EventKind::VelocityReached: return MotionEventKind::VelocityReached;
      case EventKind::Stopped: return MotionEventKind::Stopped;
      case EventKind::Deviation: return MotionEventKind::Deviation;
    }
    return MotionEventKind::Stopped;
  }

};

}  // namespace tmcl::ramp
