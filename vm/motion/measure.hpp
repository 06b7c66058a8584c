// Where the driver measures: the instants on a motor's plan at which its position counter passes
// a multiple of the measurement period (a fullstep, four with the filter 173), and the pieces of a
// segment within a speed window. Shared by the load value and stop on stall (stall_core.cpp) and
// coolStep (coolstep_core.cpp); the plan's segments are pieces of constant jerk (ramp.hpp).
#pragma once

#include <algorithm>
#include <cmath>

#include "ramp.hpp"

namespace tmcl::sw::meas {

using ramp::Segment;

inline constexpr double kTol = 1e-9;

// |v| on [t1, t2] of a segment (plan seconds) is monotone (constant jerk, one direction); the
// instant in it where |v| = c, by the closed form or bisection. c lies between the ends.
inline double speed_at(const Segment& seg, double t) { return std::fabs(seg.v(t - seg.t0)); }
inline double when_speed(const Segment& seg, double t1, double t2, double c) {
  if (seg.j == 0 && seg.a0 != 0) {
    const double t = seg.t0 + (seg.dir * c - seg.v0) / seg.a0;
    return std::clamp(t, t1, t2);
  }
  const bool rising = speed_at(seg, t2) >= speed_at(seg, t1);
  double lo = t1, hi = t2;
  for (int i = 0; i < 80 && hi - lo > 1e-12; ++i) {
    const double mid = (lo + hi) / 2;
    ((speed_at(seg, mid) < c) == rising ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

// The part of [t1, t2] where vlo <= |v| < vhi: false when empty.
inline bool speed_window(const Segment& seg, double& t1, double& t2, double vlo, double vhi) {
  if (!(vlo < vhi)) return false;
  const double e2 = std::isinf(t2) ? t1 : t2;  // the last, infinite segment keeps its speed
  const double s1 = speed_at(seg, t1), s2 = speed_at(seg, e2);
  const double lo_s = std::min(s1, s2), hi_s = std::max(s1, s2);
  if (hi_s < vlo || lo_s >= vhi) return false;
  if (s2 >= s1) {  // rising (or constant)
    if (s1 < vlo) t1 = when_speed(seg, t1, e2, vlo);
    if (s2 >= vhi) t2 = when_speed(seg, t1, e2, vhi);
  } else {
    if (s1 >= vhi) t1 = when_speed(seg, t1, e2, vhi);
    if (s2 < vlo) t2 = when_speed(seg, t1, e2, vlo);
  }
  return t1 <= t2;
}

// The segment from instant t on (its own t0 = t).
inline Segment from(const Segment& seg, double t) {
  const double dt = t - seg.t0;
  return {t, seg.dur - dt, seg.x(dt), seg.v(dt), seg.a(dt), seg.j, seg.dir};
}

// The first instant in [t1, t2] at which the counter (plan x + cbase) passes a multiple of P
// moving seg.dir; -1 when none.
inline double first_point(const Segment& seg, double t1, double t2, double cbase, double P) {
  const Segment s = from(seg, t1);
  const double c = cbase + s.x0;
  const double k = seg.dir > 0 ? std::ceil((c - kTol) / P) * P : std::floor((c + kTol) / P) * P;
  const double dt = ramp::crossing(s, k - cbase);
  if (dt < 0 || t1 + dt > t2 + kTol) return -1;
  return t1 + dt;
}

// The last such instant in [t1, t2]; -1 when none.
inline double last_point(const Segment& seg, double t1, double t2, double cbase, double P) {
  const double c = cbase + seg.x(t2 - seg.t0);
  const double k = seg.dir > 0 ? std::floor((c + kTol) / P) * P : std::ceil((c - kTol) / P) * P;
  const Segment s = from(seg, t1);
  const double dt = ramp::crossing(s, k - cbase);
  if (dt < 0 || t1 + dt > t2 + kTol) return -1;
  return t1 + dt;
}

}  // namespace tmcl::sw::meas
