// Property tests of the ramp planner (vm/ramp.hpp) over thousands of random parameter sets and
// random mid-move changes: the invariants of design/ramps.md section 9. The analytic minimum
// times are computed here independently of the planner (formulas of ramps.md sections 2-4).
#include <random>

#include "check.hpp"
#include "helpers.hpp"
#include "ramp.hpp"

using namespace tmcl::ramp;
using mt::near;

namespace {

#ifdef TMCL_MOTION_QUICK
constexpr int kCases = 600;
#else
constexpr int kCases = 4000;
#endif

struct Rng {
  std::mt19937_64 g;
  explicit Rng(std::uint64_t seed) : g(seed) {}
  double uni(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); }
  double log(double lo, double hi) { return std::exp(uni(std::log(lo), std::log(hi))); }
  bool coin(double p = 0.5) { return uni(0, 1) < p; }
  double whole(double lo, double hi) { return std::round(log(lo, hi)); }
};

enum class Kind { Trapezoid, SixPoint, SCurve };

struct Case {
  Kind kind;
  Limits lim;
};

Case random_case(Rng& r) {
  Case c;
  int k = static_cast<int>(r.uni(0, 3));
  c.kind = static_cast<Kind>(std::min(k, 2));
  Limits& l = c.lim;
  l.vmax = r.whole(10, 2e6);
  l.amax = r.whole(100, 1e7);
  l.dmax = r.coin() ? l.amax : r.whole(100, 1e7);
  l.astart = l.amax;
  l.dfinal = l.dmax;
  if (c.kind == Kind::SixPoint) {
    l.vbreak = r.whole(1, l.vmax);
    l.astart = r.whole(100, 1e7);
    l.dfinal = r.whole(100, 1e7);
  }
  if (c.kind == Kind::SCurve) {
    double j = r.whole(1e3, 1e9);
    bool sym = r.coin(0.3);
    l.ij1 = 1 / (sym ? j : r.whole(1e3, 1e9));
    l.ij2 = 1 / (sym ? j : r.whole(1e3, 1e9));
    l.ij3 = 1 / (sym ? j : r.whole(1e3, 1e9));
    l.ij4 = 1 / (sym ? j : r.whole(1e3, 1e9));
  }
  if (r.coin(0.25)) l.vstart = std::min(l.vmax, r.whole(1, l.vmax));
  if (r.coin(0.25)) l.vstop = std::min(l.vmax, r.whole(1, l.vmax));
  if (l.vstart > l.vstop && r.coin(0.7)) l.vstop = l.vstart;  // Trinamic's rule, mostly kept
  return c;
}

// ---- independent analytic minimum time (rest to rest, from the start velocity) ----

// Linear/SixPoint: distance and time of a leg between speeds with piecewise-constant rates.
struct DT {
  double s, t;
};
DT linear_acc(const Limits& l, double v0, double v1) {
  DT r{0, 0};
  auto part = [&](double a, double b, double rate) {
    if (b > a) r.s += (b * b - a * a) / (2 * rate), r.t += (b - a) / rate;
  };
  if (l.vbreak > 0) {
    part(v0, std::min(v1, l.vbreak), l.astart);
    part(std::max(v0, l.vbreak), v1, l.amax);
  } else {
    part(v0, v1, l.amax);
  }
  return r;
}
DT linear_dec(const Limits& l, double v0, double v1) {  // from v0 down to v1
  DT r{0, 0};
  auto part = [&](double a, double b, double rate) {
    if (b > a) r.s += (b * b - a * a) / (2 * rate), r.t += (b - a) / rate;
  };
  if (l.vbreak > 0) {
    part(v1, std::min(v0, l.vbreak), l.dfinal);
    part(std::max(v1, l.vbreak), v0, l.dmax);
  } else {
    part(v1, v0, l.dmax);
  }
  return r;
}

// S-curve leg of ramps.md section 4 for a speed change dv >= 0: time, and the distance u covered
// relative to the start speed (accel) by integrating its three constant-jerk phases.
DT s_leg(double dv, double Jr_inv, double Jf_inv, double A) {
  double k = (Jr_inv + Jf_inv) / 2, t1, t2, t3, ap;
  if (dv >= A * A * k) {
    ap = A, t1 = A * Jr_inv, t2 = (dv - A * A * k) / A, t3 = A * Jf_inv;
  } else {
    ap = std::sqrt(dv / k), t1 = ap * Jr_inv, t2 = 0, t3 = ap * Jf_inv;
  }
  double jr = Jr_inv > 0 ? 1 / Jr_inv : 0, jf = Jf_inv > 0 ? 1 / Jf_inv : 0;
  double u = 0, v = 0, a = 0;
  auto run = [&](double tau, double j) {
    u += v * tau + a * tau * tau / 2 + j * tau * tau * tau / 6;
    v += a * tau + j * tau * tau / 2;
    a += j * tau;
  };
  if (Jr_inv == 0) a = ap;  // no rising phase: the acceleration jumps
  run(t1, jr);
  run(t2, 0);
  run(t3, -jf);
  return {u, t1 + t2 + t3};
}

// Peak velocity, distance and time of the fastest rest-to-rest profile (bisection on vp).
double analytic_time(const Case& c, double D) {
  const Limits& l = c.lim;
  double vs = std::min(l.vstart, l.vmax), ve = l.vstop;
  bool s = c.kind == Kind::SCurve;
  auto total = [&](double vp, double& t) {
    DT a, d{0, 0};
    if (s) {
      DT u = s_leg(vp - vs, vs > 0 ? 0 : l.ij1, l.ij2, l.amax);
      a = {vs * u.t + u.s, u.t};
      if (vp > ve) {
        DT w = s_leg(vp - ve, l.ij3, ve > 0 ? 0 : l.ij4, l.dmax);
        d = {vp * w.t - w.s, w.t};  // ramps.md: vp * t - u_dec, not ve * t + u
      }
    } else {
      a = linear_acc(l, vs, vp);
      if (vp > ve) d = linear_dec(l, vp, ve);
    }
    t = a.t + d.t;
    return a.s + d.s;
  };
  double t = 0;
  if (total(vs, t) > D) {  // the start velocity is lowered (docs/motion.md)
    double lo = 0, hi = vs;
    for (int i = 0; i < 200; ++i) {
      double m = (lo + hi) / 2, tt;
      vs = m;
      (total(m, tt) <= D ? lo : hi) = m;
    }
    vs = lo;
  }
  double sV = total(l.vmax, t);
  if (sV <= D) return t + (D - sV) / l.vmax;
  double lo = vs, hi = l.vmax;
  for (int i = 0; i < 300; ++i) {
    double m = (lo + hi) / 2;
    (total(m, t) <= D ? lo : hi) = m;
  }
  double sl = total(lo, t);
  return t + (lo > 0 ? (D - sl) / lo : 0);
}

// ---- invariant checks on one plan ----
struct Report {
  bool ok = true;
  const char* why = "";
  void fail(const char* w) {
    if (ok) why = w;
    ok = false;
  }
};

// Checks a plan that starts in `start` and must end at rest on `target`.
Report check_plan(const Plan& p, const Limits& l, State start, double target, bool unchanged, double vbound,
                  double abound) {
  Report r;
  const auto& s = p.segs;
  if (s.empty() || s.back().dur != kInf) return r.fail("no final segment"), r;
  const Segment& last = s.back();
  if (last.x0 != target || last.v0 != 0 || last.a0 != 0 || last.j != 0) r.fail("not at rest on the target");
  if (p.events.empty() || p.events.back().kind != EventKind::TargetReached || p.events.back().t != p.t_rest)
    r.fail("no target-reached event at the end");
  double scale = std::max(1.0, std::fabs(target - start.x));
  double amax = std::max(std::max(l.amax, l.astart), std::max(l.dmax, l.dfinal));
  int reversals = 0, prev_dir = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Segment& g = s[i];
    if (i > 0) {
      const Segment& h = s[i - 1];
      if (!near(h.t0 + h.dur, g.t0, 1e-12, 1e-12)) r.fail("segments not contiguous");
      double xe = h.x(h.dur), ve = h.v(h.dur), ae = h.a(h.dur);
      // a rest point (the previous segment ended stopped, or at the stop-velocity cut-off): there
      // the motor may snap onto its last step, jump to the start velocity, change acceleration
      double vtol = 1e-9 * std::max(1.0, l.vmax) + 1e-9;
      bool rest_point = std::fabs(ve) <= l.vstop * (1 + 1e-9) + vtol || (i == 1 && unchanged);
      bool v_jump_ok = rest_point && std::fabs(g.v0) <= std::max(l.vstart, l.vstop) * (1 + 1e-9) + vtol;
      if (!near(xe, g.x0, 1e-9, 1e-7 * scale) && !(rest_point && std::fabs(xe - g.x0) < 1)) r.fail("position jumps");
      if (!near(ve, g.v0, 1e-9, 1e-7 * scale) && !v_jump_ok) r.fail("velocity jumps");
      if (l.s_curve() && unchanged && !rest_point && !near(ae, g.a0, 1e-6, 1e-6 * amax)) r.fail("acceleration jumps in an S-curve");
    }
    if (g.dur == kInf) break;
    // velocity at both ends and at the interior extremum
    double ts[3] = {0, g.dur, g.j != 0 ? -g.a0 / g.j : -1};
    for (double t : ts) {
      if (t < 0 || t > g.dur) continue;
      double v = g.v(t);
      if (std::fabs(v) > vbound * (1 + 1e-9) + 1e-9) r.fail("speed above its limit");
      if (g.dir != 0 && v * g.dir < -1e-7 * std::max(1.0, vbound)) r.fail("velocity changes sign inside a segment");
    }
    for (double t : {0.0, g.dur}) {
      if (std::fabs(g.a(t)) > abound * (1 + 1e-9) + 1e-9) r.fail("acceleration above its limit");
      // speeding up within the accel limits, slowing down within the decel limits
      double a = g.a(t), v = g.v(t);
      if (std::fabs(v) < 1e-6 * std::max(1.0, l.vmax)) continue;  // at rest: no direction to judge
      if (unchanged && v * a > 0 && std::fabs(a) > std::max(l.amax, l.astart) * (1 + 1e-9)) r.fail("accel limit");
      if (unchanged && v * a < 0 && std::fabs(a) > std::max(l.dmax, l.dfinal) * (1 + 1e-9)) r.fail("decel limit");
    }
    if (unchanged) {
      if (!l.s_curve() && g.j != 0) r.fail("jerk in a linear ramp");
      if (l.s_curve() && g.j != 0) {
        bool is_bow = false;
        for (double ij : {l.ij1, l.ij2, l.ij3, l.ij4})
          if (ij > 0 && near(std::fabs(g.j), 1 / ij, 1e-9)) is_bow = true;
        if (!is_bow) r.fail("jerk is not one of the bows");
      }
    }
    // monotone position, no overshoot on an unchanged move
    double x0 = g.x0, x1 = g.x(g.dur);
    if (g.dir != 0 && (x1 - x0) * g.dir < -1e-9 * scale) r.fail("position not monotone in a segment");
    if (unchanged) {
      double lo = std::min(start.x, target) - 1e-6 * scale, hi = std::max(start.x, target) + 1e-6 * scale;
      if (x1 < lo || x1 > hi) r.fail("overshoot on an unchanged move");
    }
    if (g.dir != 0) {
      if (prev_dir != 0 && g.dir != prev_dir) ++reversals;
      prev_dir = g.dir;
    }
  }
  if (reversals > 1) r.fail("more than one reversal");
  return r;
}

}  // namespace

TEST(property_unchanged_moves) {
  Rng r(12345);
  int failures = 0, checked_time = 0;
  for (int n = 0; n < kCases; ++n) {
    Case c = random_case(r);
    double D = r.whole(1, 1e7) * (r.coin() ? 1 : -1);
    Plan p;
    Builder b(p, {0, 0, 0, 0});
    b.plan_position(c.lim, D);
    double amax = std::max(std::max(c.lim.amax, c.lim.astart), std::max(c.lim.dmax, c.lim.dfinal));
    Report rep = check_plan(p, c.lim, {0, 0, 0, 0}, D, true, c.lim.vmax, amax);
    double T = analytic_time(c, std::fabs(D));
    bool time_ok = near(p.t_rest, T, 1e-8, 1e-9);
    ++checked_time;
    if (!rep.ok || !time_ok) {
      if (++failures <= 5)
        std::fprintf(stderr, "case %d kind %d D=%g V=%g A=%g Dm=%g vs=%g ve=%g vb=%g: %s; T=%.12g analytic %.12g\n", n,
                     static_cast<int>(c.kind), D, c.lim.vmax, c.lim.amax, c.lim.dmax, c.lim.vstart, c.lim.vstop,
                     c.lim.vbreak, rep.ok ? "time" : rep.why, p.t_rest, T);
    }
  }
  CHECK_EQ(failures, 0);
  CHECK_EQ(checked_time, kCases);
}

TEST(property_mid_move_changes) {
  Rng r(777);
  int failures = 0;
  for (int n = 0; n < kCases; ++n) {
    Case c = random_case(r);
    double D = r.whole(1, 1e7) * (r.coin() ? 1 : -1);
    Plan p;
    Builder b(p, {0, 0, 0, 0});
    b.plan_position(c.lim, D);
    double tc = r.uni(0, p.t_rest);
    const Segment& seg = p.segs[p.find(tc)];
    State st = p.at(tc);
    st.t = 0;
    // change: target, speed, acceleration or a bow, or several
    Case c2 = c;
    double target = D;
    if (r.coin()) target = std::round(st.x + r.log(1, 1e7) * (r.coin() ? 1 : -1));
    if (r.coin(0.4)) c2.lim.vmax = r.whole(10, 2e6), c2.lim.vstart = std::min(c2.lim.vstart, c2.lim.vmax);
    if (r.coin(0.4)) c2.lim.amax = c2.lim.astart = r.whole(100, 1e7);
    if (r.coin(0.3)) c2.lim.dmax = c2.lim.dfinal = r.whole(100, 1e7);
    Plan q;
    Builder b2(q, st, seg.dir);
    b2.plan_position(c2.lim, target);
    // bounds: the new limits, or what the state already has (a lowered VMAX is approached from above)
    double unwind = std::fabs(st.v) + (st.a * st.v > 0 ? st.a * st.a * c.lim.ij2 / 2 : 0);
    double vb = std::max(c2.lim.vmax, unwind);
    double ab = std::max({c2.lim.amax, c2.lim.astart, c2.lim.dmax, c2.lim.dfinal, std::fabs(st.a)});
    Report rep = check_plan(q, c2.lim, st, target, false, vb, ab);
    // continuity with the old plan at the change
    bool cut = std::fabs(st.v) <= c2.lim.vstop * (1 + 1e-9);  // the stop-velocity cut-off: v := 0 at once
    // after a cut-off (or from rest) the motor restarts from its last step, maybe at VSTART
    bool restart = (st.v == 0 || cut) && std::fabs(q.segs[0].x0 - st.x) < 1 &&
                   std::fabs(q.segs[0].v0) <= c2.lim.vstart * (1 + 1e-9);
    if (!q.segs.empty() && !restart) {
      if (!near(q.segs[0].x0, st.x, 1e-12, 1e-9) || !near(q.segs[0].v0, st.v, 1e-12, 1e-9)) rep.fail("re-plan not continuous");
    }
    // time at least the rest-to-rest minimum from the same place when starting at rest
    if (!rep.ok) {
      if (++failures <= 5)
        std::fprintf(stderr, "change case %d kind %d: %s (x=%g v=%g a=%g target=%g vstop=%g vstart=%g; seg0 x=%g v=%g)\n", n,
                     static_cast<int>(c.kind), rep.why, st.x, st.v, st.a, target, c2.lim.vstop, c2.lim.vstart, q.segs[0].x0,
                     q.segs[0].v0);
      if (failures <= 2) {
        std::fprintf(stderr, "  V=%.17g A=%.17g D=%.17g as=%.17g df=%.17g vb=%.17g ij=%.17g %.17g %.17g %.17g\n  st %.17g %.17g %.17g dir %d\n",
                     c2.lim.vmax, c2.lim.amax, c2.lim.dmax, c2.lim.astart, c2.lim.dfinal, c2.lim.vbreak, c2.lim.ij1, c2.lim.ij2,
                     c2.lim.ij3, c2.lim.ij4, st.x, st.v, st.a, seg.dir);
        for (const auto& g : q.segs) std::fprintf(stderr, "   seg t0=%g dur=%g x0=%g v0=%g a0=%g j=%g\n", g.t0, g.dur, g.x0, g.v0, g.a0, g.j);
      }
    }
  }
  CHECK_EQ(failures, 0);
}

TEST(property_velocity_mode) {
  Rng r(4242);
  int failures = 0;
  for (int n = 0; n < kCases; ++n) {
    Case c = random_case(r);
    c.lim.vstart = c.lim.vstop = 0;
    double v1 = r.whole(1, 1e6) * (r.coin() ? 1 : -1);
    double v2 = r.coin(0.2) ? 0 : r.whole(1, 1e6) * (r.coin() ? 1 : -1);
    Plan p;
    Builder b(p, {0, 0, 0, 0});
    b.plan_velocity(c.lim, v1);
    double tc = p.events.empty() ? 0 : p.events[0].t * r.uni(0.2, 1.5);
    State st = p.at(tc);
    st.t = 0;
    Plan q;
    Builder b2(q, st, p.segs[p.find(tc)].dir);
    b2.plan_velocity(c.lim, v2);
    const Segment& last = q.segs.back();
    bool ok = last.dur == kInf && last.v0 == v2 && last.a0 == 0 && !q.events.empty();
    // passes zero at most once; with a0 == 0 the speed moves monotonically toward the target
    int zeros = 0;
    for (std::size_t i = 1; i < q.segs.size(); ++i)
      if (q.segs[i].dir != 0 && q.segs[i - 1].dir != 0 && q.segs[i].dir != q.segs[i - 1].dir) ++zeros;
    if (zeros > 1) ok = false;
    if (st.a == 0) {
      double lo = std::min(st.v, v2), hi = std::max(st.v, v2);
      for (const auto& g : q.segs) {
        if (g.dur == kInf) break;
        double ve = g.v(g.dur);
        if (ve < lo - 1e-6 * std::max(1.0, hi - lo) || ve > hi + 1e-6 * std::max(1.0, hi - lo)) ok = false;
      }
    }
    if (!ok && ++failures <= 5)
      std::fprintf(stderr, "velocity case %d kind %d: v=%g a=%g -> %g\n", n, static_cast<int>(c.kind), st.v, st.a, v2);
  }
  CHECK_EQ(failures, 0);
}

TEST(analytic_formulas_of_ramps_md) {
  // the closed forms of ramps.md used above agree with the reference table
  Case t1{Kind::Trapezoid, {}};
  t1.lim.vmax = 51200, t1.lim.amax = t1.lim.dmax = t1.lim.astart = t1.lim.dfinal = 51200;
  CHECK(near(analytic_time(t1, 100000), 2.953125));
  CHECK(near(analytic_time(t1, 10000), 0.883883476, 1e-9));
  Case s1 = t1;
  s1.kind = Kind::SCurve;
  s1.lim.ij1 = s1.lim.ij2 = s1.lim.ij3 = s1.lim.ij4 = 1.0 / 512000;
  CHECK(near(analytic_time(s1, 100000), 3.053125));
  CHECK(near(analytic_time(s1, 1000), 0.396850263, 1e-9));
}
