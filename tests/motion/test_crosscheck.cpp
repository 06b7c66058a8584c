// Independent brute-force cross-checks with a fixed time step (1 µs or 10 µs), sharing no code
// with the planner:
//  - trapezoid/SixPoint: a step-by-step controller that brakes as soon as its braking distance
//    reaches the remaining distance (what a hardware ramp generator does every clock);
//  - S-curve: the fastest rest-to-rest profile found by bisection on a peak velocity whose legs
//    are simulated step by step with the jerk rules (raise |a| until the limit or until the rest
//    of the speed change is just what lowering |a| again will add);
//  - any plan: integrating its jerk step by step reproduces its positions.
#include <random>

#include "check.hpp"
#include "helpers.hpp"
#include "ramp.hpp"

using namespace tmcl::ramp;

namespace {

#ifdef TMCL_MOTION_QUICK
constexpr int kLinearCases = 4, kSCases = 2, kJerkCases = 20;
#else
constexpr int kLinearCases = 14, kSCases = 6, kJerkCases = 200;
#endif

// Braking distance from speed v with the decel set (piecewise constant), down to 0.
double braking(const Limits& l, double v) {
  if (l.vbreak > 0 && v > l.vbreak)
    return (v * v - l.vbreak * l.vbreak) / (2 * l.dmax) + l.vbreak * l.vbreak / (2 * l.dfinal);
  double d = l.vbreak > 0 ? l.dfinal : l.dmax;
  return v * v / (2 * d);
}

// Fixed-step controller for a rest-to-rest trapezoid/SixPoint move of D steps, as a hardware
// generator runs it every clock: of "accelerate", "cruise", "decelerate" take the first whose
// next state can still brake onto the target. Returns the arrival time, fills x every `every`
// steps.
double brute_linear(const Limits& l, double D, double dt, std::vector<double>& xs, int every) {
  double x = 0, v = 0, t = 0;
  for (long n = 0; n < 2000000000L; ++n) {
    if (n % every == 0) xs.push_back(x);
    if (D - x <= 1e-6) return t;
    double acc = v < l.vbreak ? l.astart : l.amax;
    double dec = l.vbreak > 0 && v <= l.vbreak ? l.dfinal : l.dmax;
    double options[3] = {std::min(acc, (l.vmax - v) / dt), 0, -dec};
    double v1 = 0, x1 = x;
    for (double a : options) {
      v1 = std::max(0.0, v + a * dt);
      double tau = a < 0 && v + a * dt < 0 ? v / -a : dt;  // stops inside the step
      x1 = x + v * tau + a * tau * tau / 2;
      if (braking(l, v1) <= D - x1 + 1e-9) break;
    }
    if (x1 >= D - 0.5) {  // half a step before the target: the time is well conditioned there
      double tt = std::min(dt, (D - 0.5 - x) / ((v + v1) / 2));
      return t + tt;
    }
    x = x1;
    v = v1;
    t += dt;
  }
  return t;
}

// One S-curve leg simulated with step dt: speed change dv from a = 0 to a = 0 with rising jerk
// jr, falling jerk jf, limit A. Returns time and distance relative to the start speed.
void brute_leg(double dv, double jr, double jf, double A, double dt, double& time, double& dist) {
  double v = 0, a = 0, x = 0, t = 0;
  bool falling = false;
  while (true) {
    // what lowering a to 0 from here adds to v
    if (!falling && v + a * a / (2 * jf) >= dv) falling = true;
    if (!falling) {  // would the rising step pass the switching point? then rise only until it
      double j0 = a < A ? jr : 0, an = std::min(A, a + j0 * dt);
      double vn = v + (a + an) / 2 * dt;
      if (vn + an * an / (2 * jf) > dv) {
        double lo = 0, hi = dt;
        for (int i = 0; i < 60; ++i) {
          double m = (lo + hi) / 2, am = std::min(A, a + j0 * m);
          (v + (a + am) / 2 * m + am * am / (2 * jf) > dv ? hi : lo) = m;
        }
        double am = std::min(A, a + j0 * lo);
        x += v * lo + a * lo * lo / 2 + j0 * lo * lo * lo / 6;
        v += (a + am) / 2 * lo;
        a = am;
        t += lo;
        falling = true;
      }
    }
    double j = falling ? -jf : (a < A ? jr : 0);
    double a1 = std::min(A, a + j * dt);
    if (falling && a1 <= 0) {
      double tau = a / jf;  // finish the last partial step exactly
      x += v * tau + a * tau * tau / 2 - jf * tau * tau * tau / 6;
      t += tau;
      break;
    }
    x += v * dt + a * dt * dt / 2 + j * dt * dt * dt / 6;
    v += (a + a1) / 2 * dt;
    a = a1;
    t += dt;
  }
  time = t;
  dist = x;
}

double brute_s_time(const Limits& l, double D, double dt) {
  double jr1 = 1 / l.ij1, jf1 = 1 / l.ij2, jr2 = 1 / l.ij3, jf2 = 1 / l.ij4;
  auto total = [&](double vp, double& t) {
    double ta, sa, td, sd;
    brute_leg(vp, jr1, jf1, l.amax, dt, ta, sa);
    brute_leg(vp, jr2, jf2, l.dmax, dt, td, sd);
    t = ta + td;
    return sa + (vp * td - sd);
  };
  double t;
  double s = total(l.vmax, t);
  if (s <= D) return t + (D - s) / l.vmax;
  double lo = 0, hi = l.vmax;
  for (int i = 0; i < 40; ++i) {
    double m = (lo + hi) / 2;
    (total(m, t) <= D ? lo : hi) = m;
  }
  s = total(lo, t);
  return t + (D - s) / lo;
}

}  // namespace

TEST(crosscheck_linear_controller) {
  std::mt19937_64 g(99);
  auto pick = [&](double lo, double hi) { return std::round(std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(g))); };
  for (int n = 0; n < kLinearCases; ++n) {
    Limits l;
    l.vmax = pick(500, 100000);
    l.amax = l.astart = pick(2000, 200000);
    l.dmax = l.dfinal = pick(2000, 200000);
    if (n % 2) {
      l.vbreak = pick(100, l.vmax);
      l.astart = pick(2000, 200000);
      l.dfinal = pick(2000, 200000);
    }
    double D = pick(100, 200000);
    Plan p;
    Builder b(p, {0, 0, 0, 0});
    b.plan_position(l, D);
    const double dt = 1e-6;
    const int every = 10000;  // compare every 10 ms
    std::vector<double> xs;
    double T = brute_linear(l, D, dt, xs, every);
    // the plan's instant of x = D - 0.5 (the end itself is ill-conditioned: the speed is 0 there)
    double Tp = -1;
    for (const auto& sg : p.segs) {
      double c = crossing(sg, D - 0.5);
      if (c >= 0) {
        Tp = sg.t0 + c;
        break;
      }
    }
    if (!(std::fabs(T - Tp) < 20 * dt + 1e-6 * p.t_rest)) {
      std::fprintf(stderr, "linear case %d: plan %.9g brute %.9g (V %g A %g D %g as %g vb %g df %g, dist %g)\n", n, Tp, T,
                   l.vmax, l.amax, l.dmax, l.astart, l.vbreak, l.dfinal, D);
      CHECK(false);
    }
    for (std::size_t i = 0; i < xs.size(); ++i) {
      double t = static_cast<double>(i) * every * dt;
      double x = p.at(t).x;
      if (std::fabs(x - xs[i]) > 1.0) {
        std::fprintf(stderr, "linear case %d at %g s: plan %g brute %g\n", n, t, x, xs[i]);
        CHECK(false);
        break;
      }
    }
  }
}

TEST(crosscheck_s_curve_bisection) {
  std::mt19937_64 g(5);
  auto pick = [&](double lo, double hi) { return std::round(std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(g))); };
  for (int n = 0; n < kSCases; ++n) {
    Limits l;
    l.vmax = pick(5000, 60000);
    l.amax = l.astart = pick(20000, 200000);
    l.dmax = l.dfinal = pick(20000, 200000);
    l.ij1 = 1 / pick(1e5, 4e6);
    l.ij2 = 1 / pick(1e5, 4e6);
    l.ij3 = 1 / pick(1e5, 4e6);
    l.ij4 = 1 / pick(1e5, 4e6);
    double D = pick(200, 100000);
    Plan p;
    Builder b(p, {0, 0, 0, 0});
    b.plan_position(l, D);
    double T = brute_s_time(l, D, 1e-5);
    if (!(std::fabs(T - p.t_rest) < 1e-4 * p.t_rest + 5e-5)) {
      std::fprintf(stderr, "S case %d: plan %.9g brute %.9g (V %g A %g D %g bows %g %g %g %g dist %g)\n", n, p.t_rest, T,
                   l.vmax, l.amax, l.dmax, 1 / l.ij1, 1 / l.ij2, 1 / l.ij3, 1 / l.ij4, D);
      CHECK(false);
    }
  }
}

TEST(crosscheck_integrating_the_jerk) {
  std::mt19937_64 g(31);
  auto pick = [&](double lo, double hi) { return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(g)); };
  for (int n = 0; n < kJerkCases; ++n) {
    Limits l;
    l.vmax = std::round(pick(1000, 100000));
    l.amax = l.astart = std::round(pick(5000, 500000));
    l.dmax = l.dfinal = std::round(pick(5000, 500000));
    if (n % 2) l.ij1 = 1 / pick(1e5, 1e7), l.ij2 = 1 / pick(1e5, 1e7), l.ij3 = 1 / pick(1e5, 1e7), l.ij4 = 1 / pick(1e5, 1e7);
    double D = std::round(pick(10, 50000));
    Plan p;
    Builder b(p, {0, 0, 0, 0});
    b.plan_position(l, D);
    // integrate jerk -> a -> v -> x with 10 µs steps, from the plan's own segment start values only
    // where the plan jumps (documented: start/stop velocity, snaps); elsewhere carry on.
    // step 10 µs; a step that crosses a segment boundary is split there, where the next
    // segment's acceleration (the control input) takes over
    const double dt = 1e-5;
    double x = 0, v = 0, a = p.segs[0].a0, worst = 0;
    std::size_t k = 0;
    for (double t = 0; t < p.t_rest; t += dt) {
      double from = t, to = std::min(t + dt, p.t_rest);
      while (from < to) {
        const Segment& sg = p.segs[k];
        double until = std::min(to, sg.t0 + sg.dur), h = until - from;
        x += v * h + a * h * h / 2 + sg.j * h * h * h / 6;
        v += a * h + sg.j * h * h / 2;
        a += sg.j * h;
        from = until;
        if (from >= sg.t0 + sg.dur && k + 1 < p.segs.size()) a = p.segs[++k].a0;
      }
      worst = std::max(worst, std::fabs(x - p.at(to).x));
    }
    if (worst > 1.0) {
      std::fprintf(stderr, "jerk case %d: worst %.3g steps\n", n, worst);
      CHECK(false);
    }
  }
}
