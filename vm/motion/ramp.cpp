// Closed-form ramp planning (see ramp.hpp): velocity-change legs made of constant-jerk pieces,
// positioning with the largest peak velocity that still stops on the target, velocity mode,
// the three kinds of stop, and the root of "position reaches k" inside a segment.
//
// A leg is computed in the "speed frame": the motor moves in direction dir, speed u = dir * v >= 0
// and acceleration a = dir * acc. Accelerating raises |a| with BOW1 and lowers it with BOW2;
// decelerating raises |d| with BOW3 and lowers it with BOW4 (the chip's RAMP_STATE naming).
#include "ramp.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tmcl::ramp {
namespace {

constexpr double kStepTolerance = 1e-6;  // a position this close to a whole step counts as on it

double jerk(double ij) { return ij > 0 ? 1 / ij : 0; }
int sign(double v) { return v > 0 ? 1 : v < 0 ? -1 : 0; }

// The speed bands of a ramp without bows, slowest first: [0, vbreak) at astart (dfinal),
// [vbreak, vbreak2) at amid (dmid), the rest at amax (dmax). An empty band (vbreak = 0, vbreak2 <=
// vbreak) is a phase that is skipped.
struct Band {
  double lo, hi, a;
};
std::array<Band, 3> bands(const Limits& lim, bool decel) {
  const double v1 = std::max(0.0, lim.vbreak), v2 = std::max(v1, lim.vbreak2);
  return {Band{0, v1, decel ? lim.dfinal : lim.astart}, Band{v1, v2, decel ? lim.dmid : lim.amid},
          Band{v2, kInf, decel ? lim.dmax : lim.amax}};
}

}  // namespace

bool Limits::rates() const {
  return amax > 0 && dmax > 0 && (vbreak <= 0 || (astart > 0 && dfinal > 0)) && (!mid_band() || (amid > 0 && dmid > 0));
}

bool Limits::can_move() const { return vmax > 0 && rates(); }

std::size_t Plan::find(double t) const {
  std::size_t lo = 0, hi = segs.size();
  while (hi - lo > 1) {
    std::size_t mid = (lo + hi) / 2;
    if (segs[mid].t0 <= t)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

State Plan::at(double t) const {
  const Segment& s = segs[find(t)];
  double dt = std::max(0.0, t - s.t0);
  if (dt > s.dur) dt = s.dur;
  return {t, s.x(dt), s.v(dt), s.a(dt)};
}

std::int64_t step_of(double x, int dir) {
  if (dir > 0) return static_cast<std::int64_t>(std::floor(x + kStepTolerance));
  if (dir < 0) return static_cast<std::int64_t>(std::ceil(x - kStepTolerance));
  return std::llround(x);
}

void Builder::Leg::sum(double u0) {
  t = 0;
  s = 0;
  u = u0;
  for (int i = 0; i < n; ++i) {
    double tau = p[i].tau;
    s += tau * (u + tau * (p[i].a / 2 + tau * p[i].j / 6));
    u += tau * (p[i].a + tau * p[i].j / 2);
    t += tau;
  }
}

// The speed at which the acceleration a0 has been brought back to 0 by the falling bow (0 when
// the bow is too gentle to unwind before standstill: the legs then land on (0, 0) more steeply).
double Builder::unwind(const Limits& lim, double u0, double a0) {
  if (a0 > 0) return u0 + a0 * a0 * lim.ij2 / 2;
  if (a0 < 0) return std::max(0.0, u0 - a0 * a0 * lim.ij4 / 2);
  return u0;
}

// Speed u0 (acceleration a0) up to u1 >= unwind(u0, a0), ending with a = 0.
void Builder::accel_leg(const Limits& lim, double u0, double a0, double u1, bool skip_b1, Leg& leg) {
  leg.n = 0;
  if (!lim.s_curve()) {  // trapezoid / SixPoint / EightPoint: piecewise-constant acceleration
    if (lim.mid_band()) {
      const auto b = bands(lim, false);
      for (int i = 0; i < 3; ++i) {
        double lo = std::max(u0, b[i].lo), hi = std::min(u1, b[i].hi);
        if (hi > lo) leg.add((hi - lo) / b[i].a, b[i].a, 0);
      }
      return;
    }
    double u = u0;  // two bands at most: the SixPoint ramp's own path (7 % fewer instructions a plan)
    if (lim.vbreak > 0 && u < lim.vbreak) {
      double ub = std::min(u1, lim.vbreak);
      if (ub > u) leg.add((ub - u) / lim.astart, lim.astart, 0);
      u = std::max(u, ub);
    }
    if (u1 > u) leg.add((u1 - u) / lim.amax, lim.amax, 0);
    return;
  }
  const double A = lim.amax, ij1 = skip_b1 ? 0 : lim.ij1, ij2 = lim.ij2, ij4 = lim.ij4;
  double u = u0, a = a0;
  if (a < 0) {  // still decelerating: bring |d| back to 0 with BOW4 first
    double loss = a * a * ij4 / 2;
    if (loss > u) {  // the bow cannot unwind before standstill: land on (0, 0) with a steeper jerk
      double j = u > 0 ? a * a / (2 * u) : 0;
      leg.add(j > 0 ? -a / j : 0, a, j);
      u = 0;
    } else {
      leg.add(-a * ij4, a, jerk(ij4));
      u -= loss;
    }
    a = 0;
  }
  double dv = std::max(0.0, u1 - u);
  if (a > A) {  // acceleration above the (lowered) limit: fall to it, hold, fall to 0
    double hold = std::max(0.0, (dv - a * a * ij2 / 2) / A);
    leg.add((a - A) * ij2, a, -jerk(ij2));
    leg.add(hold, A, 0);
    leg.add(A * ij2, A, -jerk(ij2));
    return;
  }
  double need = (A * A - a * a) * ij1 / 2 + A * A * ij2 / 2;  // velocity gained reaching A and back
  if (dv >= need) {
    leg.add((A - a) * ij1, a, jerk(ij1));
    leg.add((dv - need) / A, A, 0);
    leg.add(A * ij2, A, -jerk(ij2));
  } else {
    double ap = std::max(a, std::sqrt((dv + a * a * ij1 / 2) / ((ij1 + ij2) / 2)));
    leg.add((ap - a) * ij1, a, jerk(ij1));
    leg.add(ap * ij2, ap, -jerk(ij2));
  }
}

// Speed u0 (acceleration a0) down to u1 <= unwind(u0, a0), ending with a = 0 (with skip_b4 the
// deceleration is still |d| at the end: the stop-velocity cut-off follows).
void Builder::decel_leg(const Limits& lim, double u0, double a0, double u1, bool skip_b4, Leg& leg) {
  leg.n = 0;
  if (!lim.s_curve()) {
    if (lim.mid_band()) {
      const auto b = bands(lim, true);
      for (int i = 2; i >= 0; --i) {
        double lo = std::max(u1, b[i].lo), hi = std::min(u0, b[i].hi);
        if (hi > lo) leg.add((hi - lo) / b[i].a, -b[i].a, 0);
      }
      return;
    }
    double u = u0;
    if (lim.vbreak > 0 && u > lim.vbreak) {
      double ub = std::max(u1, lim.vbreak);
      if (u > ub) leg.add((u - ub) / lim.dmax, -lim.dmax, 0);
      u = std::min(u, ub);
    }
    double d = lim.vbreak > 0 ? lim.dfinal : lim.dmax;
    if (u > u1) leg.add((u - u1) / d, -d, 0);
    return;
  }
  const double D = lim.dmax, ij2 = lim.ij2, ij3 = lim.ij3, ij4 = skip_b4 ? 0 : lim.ij4;
  double u = u0, a = a0;
  if (a > 0) {  // still accelerating: bring a back to 0 with BOW2 (speed still grows)
    leg.add(a * ij2, a, -jerk(ij2));
    u += a * a * ij2 / 2;
    a = 0;
  }
  double d = -a, dv = std::max(0.0, u - u1);
  if (d > 0 && d * d * ij4 / 2 > dv) {  // cannot unwind within BOW4: land with a steeper jerk
    double j = dv > 0 ? d * d / (2 * dv) : 0;
    leg.add(j > 0 ? d / j : 0, -d, j);
    return;
  }
  if (d > D) {
    double hold = std::max(0.0, (dv - d * d * ij4 / 2) / D);
    leg.add((d - D) * ij4, -d, jerk(ij4));
    leg.add(hold, -D, 0);
    leg.add(D * ij4, -D, jerk(ij4));
    return;
  }
  double need = (D * D - d * d) * ij3 / 2 + D * D * ij4 / 2;
  if (dv >= need) {
    leg.add((D - d) * ij3, -d, -jerk(ij3));
    leg.add((dv - need) / D, -D, 0);
    leg.add(D * ij4, -D, jerk(ij4));
  } else {
    double dp = std::max(d, std::sqrt((dv + d * d * ij3 / 2) / ((ij3 + ij4) / 2)));
    leg.add((dp - d) * ij3, -d, -jerk(ij3));
    leg.add(dp * ij4, -dp, jerk(ij4));
  }
}

void Builder::lead_leg(const Limits& lim, double u0, double a0, double vp, bool skip_b1, Leg& leg) {
  if (vp >= unwind(lim, u0, a0))
    accel_leg(lim, u0, a0, vp, skip_b1, leg);
  else
    decel_leg(lim, u0, a0, vp, false, leg);
}

double Builder::reach(const Limits& lim, double u0, double a0, double vp, bool skip_b1) {
  Leg leg;
  lead_leg(lim, u0, a0, vp, skip_b1, leg);
  leg.sum(u0);
  double s = leg.s;
  if (vp > lim.vstop) {
    decel_leg(lim, vp, 0, lim.vstop, lim.vstop > 0, leg);
    leg.sum(vp);
    s += leg.s;
  }
  return s;
}

void Builder::emit(const Leg& leg, int dir) {
  for (int i = 0; i < leg.n; ++i) {
    const Piece& p = leg.p[i];
    Segment seg{s_.t, p.tau, s_.x, s_.v, dir * p.a, dir * p.j, dir};
    plan_.segs.push_back(seg);
    s_.x = seg.x(p.tau);
    s_.v = seg.v(p.tau);
    if (sign(s_.v) == -dir) s_.v = 0;  // rounding residue must not reverse the motor
    s_.a = seg.a(p.tau);
    s_.t += p.tau;
  }
  if (leg.n > 0) last_dir_ = dir, moved_ = true;
}

void Builder::emit_cruise(double tau, int dir) {
  if (!(tau > 0)) return;
  Segment seg{s_.t, tau, s_.x, s_.v, 0, 0, sign(s_.v) != 0 ? dir : 0};
  plan_.segs.push_back(seg);
  s_.x = seg.x(tau);
  s_.t += tau;
  s_.a = 0;
}

void Builder::snap() { s_.x = static_cast<double>(step_of(s_.x, last_dir_)); }

void Builder::start_motion(int dir, double v) {
  s_.v = dir * v;
  s_.a = 0;
  last_dir_ = dir;
}

// The ramp wait: a start from rest waits until the motor has rested lim.zero_wait (an empty
// segment at rest), as the TMC5240's TZEROWAIT holds the motor at 0 before it moves again.
void Builder::wait_at_rest(const Limits& lim) {
  if (!(lim.zero_wait > 0)) return;
  const double tau = lim.zero_wait - (s_.t - rest_at_);
  if (!(tau > 0)) return;
  plan_.segs.push_back({s_.t, tau, s_.x, 0, 0, 0, 0});
  s_.t += tau;
}

void Builder::finish_rest() {
  s_.v = 0;
  s_.a = 0;
  plan_.segs.push_back({s_.t, kInf, s_.x, 0, 0, 0, 0});
  plan_.t_rest = s_.t;
  plan_.rest_at = std::min(rest_at_, s_.t);
}

void Builder::finish_cruise() {
  s_.a = 0;
  if (s_.v == 0) return finish_rest();
  plan_.segs.push_back({s_.t, kInf, s_.x, s_.v, 0, 0, sign(s_.v)});
}

void Builder::coast() {
  if (s_.v == 0) s_.a = 0;
  finish_cruise();
}

void Builder::stop_hard() {
  if (moved_ || s_.v != 0 || s_.a != 0) rest_at_ = s_.t;
  moved_ = false;
  s_.v = 0;
  s_.a = 0;
  snap();
}

void Builder::stop_linear(double decel) {
  if (!(decel > 0) || s_.v == 0) return stop_hard();
  int dir = sign(s_.v);
  Leg leg;
  leg.add(std::fabs(s_.v) / decel, -decel, 0);
  emit(leg, dir);
  stop_hard();
}

void Builder::stop_ramp(const Limits& lim) {
  if (s_.v == 0 && s_.a == 0) return snap();
  int dir = s_.v != 0 ? sign(s_.v) : sign(s_.a);
  double u0 = std::fabs(s_.v), a0 = dir * s_.a;
  if (u0 > lim.vstop || (a0 > 0 && unwind(lim, u0, a0) > lim.vstop)) {  // else: the VSTOP cut-off
    Leg leg;
    decel_leg(lim, u0, a0, lim.vstop, lim.vstop > 0, leg);
    emit(leg, dir);
  }
  stop_hard();
}

// Largest vp in [lo, hi] with reach(vp) <= dist, given reach(lo) <= dist < reach(hi). Illinois
// (modified regula falsi): superlinear, and it keeps a bracket, so it always terminates.
namespace {
template <typename F>
double solve_increasing(F f, double lo, double hi, double dist) {
  double flo = f(lo) - dist, fhi = f(hi) - dist;
  int side = 0;
  const double tol = 1e-13 * std::max(1.0, dist);
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    double m = (lo * fhi - hi * flo) / (fhi - flo);
    if (!(m > lo && m < hi)) m = (lo + hi) / 2;
    double fm = f(m) - dist;
    if (fm <= 0) {
      lo = m;
      flo = fm;
      if (side == -1) fhi /= 2;
      side = -1;
      if (fm > -tol) break;
    } else {
      hi = m;
      fhi = fm;
      if (side == 1) flo /= 2;
      side = 1;
    }
  }
  return lo;
}
}  // namespace

// From speed u0 (acceleration a0) toward a target `dist` ahead: accelerate (or slow down) to the
// largest peak vp <= vmax from which the final deceleration still ends on the target, cruise,
// decelerate, stop on the target. Returns without emitting anything when it cannot stop in time.
void Builder::plan_ahead(const Limits& lim, int dir, double u0, double a0, double dist, double target,
                         bool skip_b1) {
  const double V = lim.vmax;
  auto f = [&](double vp) { return reach(lim, u0, a0, vp, skip_b1); };
  double vp = V;
  if (f(V) > dist) {
    double ulo = unwind(lim, u0, a0);
    double lo = ulo <= V ? ulo : std::max(std::min(lim.vstop, V), V * 1e-12);
    vp = solve_increasing(f, lo, V, dist);
  }
  Leg leg;
  lead_leg(lim, u0, a0, vp, skip_b1, leg);
  emit(leg, dir);
  double s_dec = 0;
  Leg dec;
  bool has_dec = vp > lim.vstop;
  if (has_dec) {
    decel_leg(lim, vp, 0, lim.vstop, lim.vstop > 0, dec);
    dec.sum(vp);
    s_dec = dec.s;
  }
  double rest = dir * (target - s_.x) - s_dec;  // what the cruise must cover
  if (rest > 0 && std::fabs(s_.v) > 0) emit_cruise(rest / std::fabs(s_.v), dir);
  if (has_dec) emit(dec, dir);
  arrive(target, dir);  // the snap: floating-point residue never leaves the motor short of the target
}

void Builder::plan_position(const Limits& lim, double target) {
  if (!lim.can_move()) return coast();
  if (s_.v == 0 && s_.a == 0) {
    snap();
    double dist = target - s_.x;
    if (std::fabs(dist) < 0.5) {
      s_.x = target;
      event(EventKind::TargetReached);
      return finish_rest();
    }
    int dir = dist > 0 ? 1 : -1;
    dist = std::fabs(dist);
    double vs = std::min(lim.vstart, lim.vmax);
    // A start velocity from which the motor cannot stop within the move (VSTART > VSTOP on a
    // short move) is lowered to the largest one that can: no overshoot-and-return cycles.
    if (vs > 0 && reach(lim, vs, 0, vs, true) > dist) {
      double lo = 0, hi = vs;
      for (int i = 0; i < 100 && hi - lo > 1e-12 * vs; ++i) {
        double m = (lo + hi) / 2;
        (reach(lim, m, 0, m, true) <= dist ? lo : hi) = m;
      }
      vs = lo;
    }
    wait_at_rest(lim);
    start_motion(dir, vs);
    return plan_ahead(lim, dir, vs, 0, dist, target, vs > 0);
  }
  int dir = s_.v != 0 ? sign(s_.v) : sign(s_.a);
  double u0 = std::fabs(s_.v), a0 = dir * s_.a;
  double dist = dir * (target - s_.x);
  // The shortest way to rest from here is the direct stop: reach(lo) below is that distance.
  double ulo = unwind(lim, u0, a0);
  double lo = ulo <= lim.vmax ? ulo : std::max(std::min(lim.vstop, lim.vmax), lim.vmax * 1e-12);
  if (dist >= 0 && reach(lim, u0, a0, lo, false) <= dist) return plan_ahead(lim, dir, u0, a0, dist, target, false);
  stop_ramp(lim);  // overshoot: stop, then come back from rest
  plan_position(lim, target);
}

void Builder::plan_velocity(const Limits& lim, double vt) {
  if (!ramp_to(lim, vt)) return coast();
  if (vt == 0) {  // at rest now
    event(EventKind::Stopped);
    return finish_rest();
  }
  event(EventKind::VelocityReached);
  finish_cruise();
}

bool Builder::ramp_to(const Limits& lim, double vt) {
  if (!lim.rates()) return false;
  int dir = s_.v != 0 ? sign(s_.v) : sign(s_.a);
  if (dir != 0 && sign(vt) != dir) stop_ramp(lim);  // reversal (or vt == 0): to rest first
  if (s_.v == 0 && s_.a == 0) {
    snap();
    if (vt == 0) return true;
    int d = sign(vt);
    double u1 = std::fabs(vt), vs = std::min(lim.vstart, u1);
    wait_at_rest(lim);
    start_motion(d, vs);
    Leg leg;
    accel_leg(lim, vs, 0, u1, vs > 0, leg);
    emit(leg, d);
  } else {
    double u0 = std::fabs(s_.v), a0 = dir * s_.a;
    Leg leg;
    lead_leg(lim, u0, a0, std::fabs(vt), false, leg);
    emit(leg, dir);
  }
  s_.v = vt;  // the leg ends on vt up to rounding; cruise exactly at it
  s_.a = 0;
  return true;
}

void Builder::piece(double tau, double a, double j, int dir) {
  Leg leg;
  leg.add(tau, a, j);
  emit(leg, dir);
}

void Builder::cruise(double tau, int dir) { emit_cruise(tau, dir); }

void Builder::arrive(double target, int dir) {
  rest_at_ = s_.t;
  moved_ = false;
  s_.x = target;
  s_.v = 0;
  s_.a = 0;
  last_dir_ = dir;
  event(EventKind::TargetReached);
  finish_rest();
}

void Builder::truncate(double t) {
  std::size_t i = plan_.find(t);
  plan_.segs.resize(i + 1);
  Segment& seg = plan_.segs[i];
  double dt = std::min(std::max(0.0, t - seg.t0), seg.dur);
  seg.dur = dt;
  s_ = {t, seg.x(dt), seg.v(dt), seg.a(dt)};
  if (seg.dir != 0) last_dir_ = seg.dir;
  if (dt == 0) plan_.segs.pop_back();
  while (!plan_.events.empty() && plan_.events.back().t > t) plan_.events.pop_back();
  plan_.t_rest = kInf;
}

double crossing(const Segment& seg, double k) {
  if (seg.dir == 0) return -1;
  double d = seg.dir;
  if (d * (seg.x0 - k) >= 0) return 0;
  if (seg.dur == kInf) {
    if (seg.j != 0 || seg.a0 != 0 || d * seg.v0 <= 0) return -1;
    return (k - seg.x0) / seg.v0;
  }
  if (d * (seg.x(seg.dur) - k) < 0) return -1;
  double lo = 0, hi = seg.dur;  // d * (x - k) < 0 at lo, >= 0 at hi
  double t = seg.dur * (k - seg.x0) / (seg.x(seg.dur) - seg.x0);
  for (int i = 0; i < 100; ++i) {
    if (!(t > lo && t < hi)) t = (lo + hi) / 2;
    double f = d * (seg.x(t) - k);
    if (f >= 0)
      hi = t;
    else
      lo = t;
    if (hi - lo <= 1e-13 * std::max(1.0, seg.t0 + seg.dur)) break;
    double v = d * seg.v(t);
    t = v > 0 ? t - f / v : (lo + hi) / 2;
  }
  return hi;
}

}  // namespace tmcl::ramp
