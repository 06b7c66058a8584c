// The reference cases of design/ramps.md and more derived by hand from its formulas, run through
// the tmc4361 core's public API: event instants (rounded up to the microsecond), final position,
// peak velocity.
#include "check.hpp"
#include "helpers.hpp"

using mt::Bench;
using mt::near;
using mt::us;
using tmcl::MotionEventKind;

namespace {

// Runs a move from rest at 0 to `target`; returns the instant of its TargetReached event.
tmcl::SimTime move(Bench& b, std::int32_t target) {
  b.core->move_absolute(0, target);
  tmcl::SimTime t = b.next();
  CHECK(!b.events.empty());
  if (b.events.empty()) return -1;
  CHECK(b.last().kind == MotionEventKind::TargetReached);
  CHECK_EQ(b.last().position, target);
  CHECK_EQ(b.core->position(0), target);
  CHECK(b.core->target_reached(0));
  CHECK_EQ(b.get(8), 1);
  return t;
}

double peak_velocity(Bench& b, tmcl::SimTime from, tmcl::SimTime to) {
  double peak = 0;
  for (tmcl::SimTime t = from; t <= to; t += 50) peak = std::max(peak, std::fabs(b.core->sample_at(0, t).velocity));
  return peak;
}

}  // namespace

TEST(reference_T1_trapezoid_long) {
  Bench b;
  CHECK_EQ(move(b, 100000), us(2.953125));
}

TEST(reference_T2_trapezoid_short) {
  Bench b;
  b.core->move_absolute(0, 10000);
  double peak = peak_velocity(b, 0, 883883);
  CHECK(near(peak, 22627.417, 1e-4));
  CHECK_EQ(b.next(), us(0.883883476));
  CHECK_EQ(b.core->position(0), 10000);
}

TEST(reference_S1_s_curve_long) {
  Bench b;
  b.set(14, 1);
  CHECK_EQ(move(b, 100000), us(3.053125));
}

TEST(reference_S3_s_curve_short) {
  Bench b;
  b.set(14, 1);
  b.core->move_absolute(0, 1000);
  double peak = peak_velocity(b, 0, 396850);
  CHECK(near(peak, 5039.684, 1e-5));
  // peak acceleration 50796.8 < AMAX: sample the acceleration near the first quarter
  double amax = 0;
  for (tmcl::SimTime t = 0; t < 396850; t += 10) amax = std::max(amax, b.core->sample_at(0, t).acceleration);
  CHECK(near(amax, 50796.8, 2e-4));
  CHECK_EQ(b.next(), us(0.396850263));
}

TEST(reference_bow_scaling) {
  Bench b;
  b.set(14, 1);
  for (int p = 22; p <= 25; ++p) b.set(p, 256000);
  b.set(35, 2);  // 256000 * 2 = 512000: the S1 case again
  CHECK_EQ(move(b, 100000), us(3.053125));
}

TEST(reference_sixpoint) {
  // accel 0->10240 at 10240 (1 s, 5120), 10240->51200 at 51200 (0.8 s, 24576);
  // decel 51200->10240 at 25600 (1.6 s, 49152), 10240->0 at 5120 (2 s, 10240); cruise 10912 at 51200.
  Bench b;
  b.set(16, 10240);
  b.set(18, 10240);
  b.set(17, 25600);
  b.set(19, 5120);
  CHECK_EQ(move(b, 100000), us(1.8 + 3.6 + 10912.0 / 51200));
}

TEST(reference_sixpoint_defaults_mean_symmetric) {
  Bench b;
  b.set(18, 10240);  // break velocity alone: 16, 17, 19 = 0 mean "as 5": still the T1 ramp
  CHECK_EQ(move(b, 100000), us(2.953125));
}

TEST(reference_final_deceleration_follows_max_deceleration) {
  // 19 = 0 means "as the effective 17": with 17 = 25600 both decel legs use 25600.
  Bench b;
  b.set(18, 10240);
  b.set(17, 25600);
  // accel 1 s (25600), decel 2 s (51200), cruise 23200 at 51200
  CHECK_EQ(move(b, 100000), us(3 + 23200.0 / 51200));
}

TEST(reference_start_and_stop_velocity) {
  // VSTART 5120, VSTOP 10240: s_a = 25344 (0.9 s), s_d = 24576 (0.8 s), cruise 50080 at 51200.
  Bench b;
  b.set(15, 5120);
  b.set(20, 10240);
  CHECK_EQ(move(b, 100000), us(0.9 + 0.8 + 50080.0 / 51200));
}

TEST(reference_short_move_below_stop_velocity) {
  // vs = 0 < ve = 10240 and D = 400 < 1024: accelerate all the way, v_end = 6400, T = 0.125 s.
  Bench b;
  b.set(20, 10240);
  b.core->move_absolute(0, 400);
  CHECK(near(b.core->sample_at(0, 124999).velocity, 6400, 1e-3));
  CHECK_EQ(b.next(), us(0.125));
  CHECK_EQ(b.core->position(0), 400);
}

TEST(reference_start_velocity_above_stop_velocity_short_move) {
  // VSTART 20000 > VSTOP 0 on a 100-step move: the start jump is lowered so that the motor can
  // still stop on the target (no overshoot and return cycles): position never passes 100.
  Bench b;
  b.set(15, 20000);
  b.core->move_absolute(0, 100);
  tmcl::SimTime t = b.core->next_event();
  for (tmcl::SimTime s = 0; s <= t; s += 10) CHECK(b.core->sample_at(0, s).position <= 100);
  b.next();
  CHECK_EQ(b.core->position(0), 100);
  // v0 = sqrt(2 * 51200 * 100) = 3200, stopping in 1/16 s
  CHECK_EQ(t, us(3200.0 / 51200));
}

namespace {
// Distance and time of constant-jerk pieces from speed v (an independent little integrator).
struct Pieces {
  double t = 0, s = 0, v = 0, a = 0;
  void run(double tau, double j) {
    s += v * tau + a * tau * tau / 2 + j * tau * tau * tau / 6;
    v += a * tau + j * tau * tau / 2;
    a += j * tau;
    t += tau;
  }
};
}  // namespace

TEST(reference_asymmetric_bows_long) {
  const double V = 51200, A = 51200, J1 = 512000, J2 = 256000, J3 = 1024000, J4 = 128000;
  Pieces acc;
  acc.run(A / J1, J1);
  acc.run((V - A * A / (2 * J1) - A * A / (2 * J2)) / A, 0);
  acc.run(A / J2, -J2);
  Pieces dec;
  dec.v = V;
  dec.run(A / J3, -J3);
  dec.run((V - A * A / (2 * J3) - A * A / (2 * J4)) / A, 0);
  dec.run(A / J4, J4);
  CHECK(near(acc.v, V));
  CHECK(std::fabs(dec.v) < 1e-6);
  const double D = 200000;
  double T = acc.t + dec.t + (D - acc.s - dec.s) / V;
  Bench b;
  b.set(14, 1);
  b.set(22, 512000);
  b.set(23, 256000);
  b.set(24, 1024000);
  b.set(25, 128000);
  CHECK_EQ(move(b, 200000), us(T));
}

TEST(reference_s_curve_with_start_and_stop_velocity) {
  // VSTART 10240: no B1 phase, a jumps to AMAX; VSTOP 10240: no B4 phase, the decel ends at
  // |d| = DMAX and v jumps to 0 at the target.
  const double V = 51200, A = 51200, J = 512000, vs = 10240;
  Pieces acc;
  acc.v = vs;
  acc.a = A;
  acc.run((V - vs - A * A / (2 * J)) / A, 0);
  acc.run(A / J, -J);
  Pieces dec;
  dec.v = V;
  dec.run(A / J, -J);
  dec.run((V - vs - A * A / (2 * J)) / A, 0);
  CHECK(near(dec.v, vs, 1e-12, 1e-6));
  const double D = 100000;
  double T = acc.t + dec.t + (D - acc.s - dec.s) / V;
  Bench b;
  b.set(14, 1);
  b.set(15, 10240);
  b.set(20, 10240);
  CHECK_EQ(move(b, 100000), us(T));
}

TEST(reference_negative_move_mirrors_positive) {
  Bench b;
  b.set(14, 1);
  CHECK_EQ(move(b, -100000), us(3.053125));
}

TEST(reference_unit_mode_internal) {
  Bench b;
  b.set(255, 0);
  b.set(4, 51200 * 256);  // 24.8 fixed point
  b.set(5, 51200 * 4);    // 22.2 fixed point
  b.core->move_absolute(0, 100000);
  b.to(1500000);
  CHECK_EQ(b.get(3), 51200 * 256);
  CHECK_EQ(b.next(), us(2.953125));
}
