// One motor's current plan in simulated time, shared by the ramp-generator cores: the plan's
// origin (an integer microsecond), the integer position its doubles are relative to, and which of
// its events have been reported. Time rounding lives here: a plan instant t (seconds, exact) is
// reported at the first whole microsecond >= t (1 ns of floating-point noise tolerated).
#pragma once

#include <cmath>
#include <cstdint>

#include "ramp.hpp"
#include "tmcl/motion.hpp"

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
  const Segment& segment(SimTime t) const { return plan.segs[plan.find(secs(t))]; }
  std::int64_t xactual(SimTime t) const {
    double s = secs(t);
    const Segment& seg = plan.segs[plan.find(s)];
    double dt = std::min(std::max(0.0, s - seg.t0), seg.dur);
    return base + step_of(seg.x(dt), seg.dir);
  }
  SimTime event_time(std::size_t i) const { return origin + ceil_us(plan.events[i].t); }
  SimTime next_event() const { return next < plan.events.size() ? event_time(next) : kNever; }
  bool at_rest(SimTime now) const { return plan.t_rest != kInf && origin + ceil_us(plan.t_rest) <= now; }
  bool moving(SimTime now) const { return !at_rest(now); }

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

}  // namespace tmcl::ramp
