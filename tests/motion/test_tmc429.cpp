// The tmc429 core through its public API: the TMC429's units against the TMCM-1110 manual's worked
// example (section 5.5), move times against the closed form over the divisors' whole range,
// velocity mode and re-targeting, the limit switches and their stop functions, switches placed at
// positions, and every mode of the reference search.
#include <cmath>
#include <string>
#include <utility>

#include "check.hpp"
#include "helpers.hpp"

using mt::Bench;
using mt::near;
using mt::move_time;
using mt::run_time;
using mt::us;
using tmcl::MotionEventKind;
using tmcl::SwitchInput;

namespace {

constexpr double kClock = 16e6;
double vunit(int pulse_div) { return std::ldexp(kClock, -(pulse_div + 16)); }
double aunit(int pulse_div, int ramp_div) { return std::ldexp(kClock * kClock, -(pulse_div + ramp_div + 29)); }

// The generic profile accepts every number; the core takes the TMCM-1110's rows. The settings
// the tests count on are set here, whatever the profile's defaults.
struct Chip : mt::SwitchBench {
  Chip() : SwitchBench("tmc429", "generic", 1) {
    for (auto [param, value] : {std::pair{154, 3}, {153, 7}, {4, 1000}, {5, 1000}, {130, 1}, {149, 0}, {12, 0}, {13, 0},
                                {193, 1}, {194, 0}, {195, 0}, {138, 0}})
      set(param, value);
  }
};

}  // namespace

TEST(tmc429_units_match_the_manuals_worked_example) {
  Chip b;  // TMCM-1110 manual 5.5: velocity 1000, a_max 1000, pulse_div 1, ramp_div 1, 16 microsteps
  b.set(154, 1);
  b.set(153, 1);
  b.set(140, 4);
  auto v = b.core->physical(0, 4, 1000);
  auto a = b.core->physical(0, 5, 1000);
  CHECK(v && a);
  CHECK(near(v->value, 122070.3125, 1e-15));
  CHECK(std::string(v->unit) == "pps");
  CHECK(std::fabs(v->value - 122070.31) < 0.005);      // the manual's 122070.31 Hz
  CHECK(std::fabs(a->value / 1e6 - 119.21) < 0.005);  // the manual's 119.21 MHz/s
  CHECK(near(a->value, 119209289.55078125, 1e-15));
  CHECK(std::string(a->unit) == "pps²");
  CHECK(!b.core->physical(0, 0, 1000));  // a position is no rate
  // And the motion: ROR 1000 reaches 122070.3125 pps after v/a.
  b.set(5, 1000);
  b.core->rotate(0, 1000);
  CHECK_EQ(b.next(), us(122070.3125 / 119209289.55078125));
  CHECK(b.last().kind == MotionEventKind::VelocityReached);
  CHECK(near(b.core->sample_at(0, 2000000).velocity, 122070.3125));
  CHECK_EQ(b.get(3), 1000);
  CHECK_EQ(b.get(2), 1000);
  CHECK(b.core->units_note().find("pulse divisor 1, ramp divisor 1: velocity 1 = 122.07 pps, acceleration 1 = 119209 pps²") !=
        std::string::npos);
}

// Under generic the defaults are the built-in tmcm-1110 profile's (not the generic profile's,
// which are the USB-2-SD's in pps).
TEST(tmc429_defaults_and_ranges_without_a_module_profile) {
  Bench d("tmc429", "generic", 1);
  const tmcl::Profile* home = tmcl::find_profile("tmcm-1110");
  CHECK(home != nullptr);
  auto expect = [&](int param, std::int32_t value) {
    CHECK_EQ(d.get(param), value);
    if (home) CHECK_EQ(home->axis_param(param)->default_value, value);
  };
  expect(4, 1000);
  expect(5, 1000);
  expect(154, 3);
  expect(153, 7);
  expect(130, 1);
  expect(193, 1);
  Chip b;
  CHECK(b.core->set_param(0, 4, 2048) == tmcl::ParamWrite::OutOfRange);
  CHECK(b.core->set_param(0, 5, -1) == tmcl::ParamWrite::OutOfRange);
  CHECK(b.core->set_param(0, 154, 14) == tmcl::ParamWrite::OutOfRange);
  CHECK(b.core->set_param(0, 2, -2048) == tmcl::ParamWrite::OutOfRange);
  CHECK(b.core->set_param(0, 193, 9) == tmcl::ParamWrite::OutOfRange);
  CHECK(b.core->set_param(0, 193, 128) == tmcl::ParamWrite::OutOfRange);
  CHECK(b.core->set_param(0, 193, 136) == tmcl::ParamWrite::Ok);
  for (int ro : {3, 8, 9, 10, 11, 135, 196}) CHECK(b.core->set_param(0, ro, 0) == tmcl::ParamWrite::ReadOnly);
  b.core->rotate(0, 5000);  // the register holds 11 bits: the speed is 2047
  CHECK_EQ(b.get(2), 2047);
}

// Closed form: T = D/v + v/a (trapezoid) or 2 sqrt(D/a) (triangle); within 1 % or 2 ms over every
// pair of divisors, with the minimum speed at its "always 1".
TEST(tmc429_move_times_match_the_closed_form_over_all_divisors) {
  int checked = 0;
  for (int pd = 0; pd <= 13; ++pd)
    for (int rd = 0; rd <= 13; ++rd)
      for (int V : {500, 1000, 2047})
        for (int A : {1, 60, 2047})
          for (double k : {0.3, 3.0}) {  // D = k v^2/a: a triangle, then a trapezoid
            const double v = V * vunit(pd), a = A * aunit(pd, rd);
            double D = std::max(50.0, std::round(k * v * v / a));
            if (D > 2e9) continue;  // beyond the position register
            Chip b;
            b.set(154, pd);
            b.set(153, rd);
            b.set(4, V);
            b.set(5, A);
            b.core->move_absolute(0, static_cast<std::int32_t>(D));
            tmcl::SimTime t = b.next();
            CHECK(b.last().kind == MotionEventKind::TargetReached);
            CHECK_EQ(b.core->position(0), static_cast<std::int32_t>(D));
            const double T = move_time(D, v, a), got = static_cast<double>(t) * 1e-6;
            if (!(std::fabs(got - T) <= std::max(0.01 * T, 0.002) + 1e-6)) {
              std::fprintf(stderr, "pd %d rd %d V %d A %d D %.0f: %.6f s, closed form %.6f s\n", pd, rd, V, A, D, got, T);
              CHECK(false);
            }
            ++checked;
          }
  CHECK(checked > 1000);
}

// With the minimum speed 0 the ramp is the closed form exactly (to the microstep's rounding).
TEST(tmc429_move_time_is_exact_without_minimum_speed) {
  Chip b;
  b.set(130, 0);
  const double v = 1000 * vunit(3), a = 1000 * aunit(3, 7);
  b.core->move_absolute(0, 100000);
  CHECK_EQ(b.next(), us(move_time(100000, v, a)));
  Chip c;
  c.set(130, 0);
  c.core->move_absolute(0, -1500);  // v^2/a = 2000 steps: a triangle
  CHECK_EQ(c.next(), us(move_time(1500, v, a)));
  CHECK_EQ(c.core->position(0), -1500);
}

TEST(tmc429_readings_are_whole_units) {
  Chip b;
  b.set(130, 0);
  const double v = 1000 * vunit(3), a = 1000 * aunit(3, 7);
  b.core->move_absolute(0, 100000);
  b.to(us(0.5 * v / a));  // half way up the ramp: 500 units, exactly
  CHECK_EQ(b.get(3), 500);
  CHECK_EQ(b.get(135), 1000);  // accelerating with a_max
  CHECK_EQ(b.get(2), 1000);    // position mode: 2 reads the maximum speed while speeding up...
  b.to(us(0.5 * v / a) + 7);
  CHECK_EQ(b.get(3), 500);  // not 500.05: whole units toward zero
  b.to(1000000);
  CHECK_EQ(b.get(3), 1000);
  CHECK_EQ(b.get(135), 0);
  CHECK_EQ(b.get(2), 1000);  // ...and cruises
  b.to(us(move_time(100000, v, a)) - 20000);
  CHECK_EQ(b.get(2), 0);  // ...and 0 while it slows down
  CHECK_EQ(b.get(135), 1000);
  CHECK(b.get(3) > 0 && b.get(3) < 1000);
  CHECK_EQ(b.get(8), 0);
  b.next();
  CHECK_EQ(b.get(8), 1);
  CHECK_EQ(b.get(2), 0);
  CHECK_EQ(b.get(138), 0);
}

TEST(tmc429_velocity_mode_reversal_and_stop) {
  Chip b;
  const double v = 1000 * vunit(3), a = 1000 * aunit(3, 7);
  b.core->rotate(0, 1000);
  CHECK_EQ(b.get(138), 2);
  CHECK_EQ(b.next(), us(v / a));
  b.to(1000000);
  b.core->rotate(0, -1000);  // ROL: through 0 to -1000 with a_max both ways
  CHECK_EQ(b.next(), 1000000 + us(2 * v / a));
  CHECK(b.last().kind == MotionEventKind::VelocityReached);
  CHECK_EQ(b.get(3), -1000);
  b.to(2000000);
  b.core->stop(0);  // MST: the ramp down
  CHECK_EQ(b.next(), 2000000 + us(v / a));
  CHECK(b.last().kind == MotionEventKind::Stopped);
  CHECK_EQ(b.get(3), 0);
}

TEST(tmc429_retargeting_a_running_move) {
  const double v = 1000 * vunit(3), a = 1000 * aunit(3, 7);
  {  // farther ahead: the move goes on as if it had been the target from the start
    Chip b;
    b.set(130, 0);
    b.core->move_absolute(0, 100000);
    b.to(1000000);
    b.core->move_absolute(0, 200000);
    CHECK_EQ(b.next(), us(move_time(200000, v, a)));
    CHECK_EQ(b.core->position(0), 200000);
  }
  {  // behind: it stops with a_max (overshooting), then comes back from rest
    Chip b;
    b.set(130, 0);
    b.core->move_absolute(0, 100000);
    b.to(1000000);
    const double x = v * v / (2 * a) + v * (1 - v / a);  // where it is at 1 s
    b.core->move_absolute(0, 10000);
    tmcl::SimTime t = b.next();
    CHECK(b.last().kind == MotionEventKind::TargetReached);
    CHECK_EQ(b.core->position(0), 10000);
    const double stop_at = std::floor(x + v * v / (2 * a));
    CHECK(std::llabs(t - (1000000 + us(v / a) + us(move_time(stop_at - 10000, v, a)))) <= 2);
  }
  {  // a new speed while cruising: the ramp to it, then on to the target
    Chip b;
    b.set(130, 0);
    b.core->move_absolute(0, 100000);
    b.to(1000000);
    b.set(4, 500);
    b.next();
    CHECK_EQ(b.core->position(0), 100000);
    CHECK(b.now > us(move_time(100000, v, a)));
  }
  {  // ROR during a move, MVP during a rotation
    Chip b;
    b.core->move_absolute(0, 100000);
    b.to(500000);
    b.core->rotate(0, 200);
    CHECK_EQ(b.next(), 500000 + us(800 * vunit(3) / a));
    CHECK_EQ(b.get(3), 200);
    b.core->move_absolute(0, 0);
    b.next();
    CHECK_EQ(b.core->position(0), 0);
    CHECK(b.core->target_reached(0));
  }
}

// Soft mode (138 = 1): near the target the speed is k = a/V times the distance left, down to
// the minimum speed, which covers the last 1/k seconds.
TEST(tmc429_soft_mode_approaches_exponentially) {
  const double V = 1000 * vunit(3), a = 1000 * aunit(3, 7), k = a / V, vmin = vunit(3);
  Chip b;
  b.set(138, 1);
  CHECK_EQ(b.core->next_event(), tmcl::kNever);  // at rest on its target (0): nothing to do
  b.core->move_absolute(0, 100000);
  CHECK_EQ(b.get(138), 1);  // MVP keeps the soft mode
  const double T = (V - vmin) / a + (100000 - (V * V - vmin * vmin) / (2 * a) - V / k) / V + std::log(V / vmin) / k + 1 / k;
  CHECK(std::llabs(b.core->next_event() - us(T)) <= 2);
  for (double d : {1500.0, 500.0, 50.0}) {  // on the exponential (the last V/k = 2000 steps): v = k d
    const double t = T - 1 / k - std::log(k * d / vmin) / k;
    const auto smp = b.core->sample_at(0, us(t));
    CHECK(std::fabs(smp.velocity - k * static_cast<double>(100000 - smp.position)) < 0.002 * smp.velocity + k);
    CHECK(std::fabs(smp.acceleration + k * smp.velocity) < 0.01 * k * smp.velocity);
  }
  b.next();
  CHECK(b.last().kind == MotionEventKind::TargetReached);
  CHECK_EQ(b.core->position(0), 100000);
  b.core->move_absolute(0, 99000);  // a short one, backwards: the same profile, lower peak
  b.next();
  CHECK_EQ(b.core->position(0), 99000);
  // A new maximum speed half way down the exponential: it goes on with the new k.
  b.core->move_absolute(0, 0);
  b.to(b.now + us((99000 - V * V / a) / V));
  b.set(4, 500);
  b.next();
  CHECK(b.last().kind == MotionEventKind::TargetReached);
  CHECK_EQ(b.core->position(0), 0);
}

TEST(tmc429_soft_mode_without_minimum_speed_stops_short) {
  Chip b;
  b.set(130, 0);
  b.set(5, 700);
  b.set(138, 1);
  b.core->move_absolute(0, 50000);
  b.to(100000000);
  const double k = 700 * aunit(3, 7) / (1000 * vunit(3));  // vunit/k = 2.86 steps
  CHECK(!b.core->target_reached(0));  // below one unit the chip's speed is 0: the last vunit/k steps
  CHECK_EQ(b.core->position(0), 50000 - static_cast<std::int32_t>(std::ceil(vunit(3) / k)));
  CHECK_EQ(b.get(8), 0);
  CHECK_EQ(b.get(3), 0);
}

TEST(tmc429_pulse_divisor_changes_the_step_rate_at_once) {
  Chip b;
  b.core->rotate(0, 1000);
  b.next();
  b.to(1000000);
  CHECK(near(b.core->sample_at(0, 1000000).velocity, 1000 * vunit(3)));
  b.set(154, 2);  // the chip keeps 1000 units: twice the microstep rate
  CHECK(near(b.core->sample_at(0, 1000000).velocity, 1000 * vunit(2)));
  CHECK(near(b.core->sample_at(0, 1500000).velocity, 1000 * vunit(2)));
  CHECK_EQ(b.get(3), 1000);
  CHECK(b.core->units_note().find("pulse divisor 2, ramp divisor 7") != std::string::npos);
}

TEST(tmc429_limit_switch_hard_stop_at_its_position) {
  const double v = 1000 * vunit(3), a = 1000 * aunit(3, 7);
  Chip b;
  b.left_at(-20000);
  b.core->rotate(0, -1000);
  CHECK(b.until(MotionEventKind::Stopped));
  const tmcl::SimTime t = us(v / a + (20000 - v * v / (2 * a)) / v);
  CHECK_EQ(b.now, t);
  CHECK_EQ(b.core->position(0), -20000);
  const auto& sw = b.events[b.events.size() - 2];  // the switch first, then the stop it caused
  CHECK(sw.kind == MotionEventKind::SwitchChanged && sw.input == SwitchInput::StopLeft && sw.active);
  CHECK_EQ(sw.at, t);
  CHECK_EQ(sw.position, -20000);
  CHECK_EQ(b.get(11), 1);
  CHECK_EQ(b.get(9), 1);
  CHECK_EQ(b.get(10), 0);
  CHECK_EQ(b.get(3), 0);
  b.core->rotate(0, -100);  // toward the closed switch: blocked at once
  CHECK_EQ(b.next(), t);
  CHECK(b.last().kind == MotionEventKind::Stopped);
  CHECK_EQ(b.core->position(0), -20000);
  b.core->move_absolute(0, -10000);  // away from it: free; it opens one step out
  CHECK(b.until(MotionEventKind::SwitchChanged));
  CHECK(!b.last().active);
  CHECK_EQ(b.last().position, -19999);
  CHECK(b.until(MotionEventKind::TargetReached));
  CHECK_EQ(b.get(11), 0);
}

TEST(tmc429_limit_switch_soft_stop_with_the_ramp) {
  const double v = 1000 * vunit(3), a = 1000 * aunit(3, 7);
  Chip b;
  b.set(149, 1);
  b.right_at(30000);
  b.core->move_absolute(0, 100000);
  CHECK(b.until(MotionEventKind::Stopped));
  // From the minimum speed (1 unit) up to v, cruise to the switch, down to the minimum speed, stop.
  const double vmin = vunit(3), ramp_s = (v * v - vmin * vmin) / (2 * a), ramp_t = (v - vmin) / a;
  const double t_hit = ramp_t + (30000 - ramp_s) / v;
  CHECK(std::fabs(static_cast<double>(b.now) * 1e-6 - (t_hit + ramp_t)) < 20e-6);
  CHECK(std::llabs(b.core->position(0) - static_cast<std::int32_t>(30000 + ramp_s)) <= 1);
  CHECK_EQ(b.get(10), 1);
  CHECK(!b.core->target_reached(0));
  CHECK_EQ(b.get(0), 100000);  // the target stays
}

TEST(tmc429_disabled_stop_function_lets_the_motor_pass) {
  Chip b;
  b.set(13, 1);
  b.left_at(-2000);
  b.core->move_absolute(0, -5000);
  CHECK(b.until(MotionEventKind::TargetReached));
  CHECK_EQ(b.core->position(0), -5000);
  CHECK_EQ(b.count(MotionEventKind::SwitchChanged), 1);
  CHECK_EQ(b.get(11), 1);
  Chip c;  // the home switch never stops the motor
  c.place(SwitchInput::Home, -150, 150);
  c.core->move_absolute(0, 5000);
  CHECK(c.until(MotionEventKind::TargetReached));
  CHECK_EQ(c.count(MotionEventKind::SwitchChanged), 2);  // closed at power-on, opened at 151
  CHECK(c.events[0].active && c.events[0].at == 0);
  CHECK(!c.events[1].active && c.events[1].position == 151);
}

TEST(tmc429_timed_switch_stops_a_rotation) {
  Chip b;
  b.core->rotate(0, 500);
  b.to(300000);
  b.core->set_switch(0, SwitchInput::StopRight, true);
  CHECK_EQ(b.next(), 300000);
  CHECK(b.last().kind == MotionEventKind::Stopped);
  CHECK_EQ(b.get(10), 1);
  CHECK_EQ(b.get(3), 0);
  b.set(12, 1);  // disabled: the same switch lets it go
  b.core->rotate(0, 500);
  CHECK(b.until(MotionEventKind::VelocityReached));
}

// Switches belong to the machine: writing the actual position moves the register only.
TEST(tmc429_switch_positions_are_physical) {
  Chip b;
  b.left_at(-1000);
  b.set(1, 5000);
  b.core->rotate(0, -300);
  CHECK(b.until(MotionEventKind::Stopped));
  CHECK_EQ(b.core->position(0), 4000);
  // Both ways, at the exact microstep: a cam on the right input, crossed at constant speed.
  Chip c;
  c.set(13, 1);
  c.set(12, 1);
  c.place(SwitchInput::StopRight, 3000, 3999);
  c.core->rotate(0, 1000);
  CHECK(c.until(MotionEventKind::VelocityReached));  // at 1000 steps, after v/a
  const double v = 1000 * vunit(3), t0 = v / (1000 * aunit(3, 7));
  CHECK(c.until(MotionEventKind::SwitchChanged));
  CHECK(c.last().active && c.last().position == 3000);
  CHECK_EQ(c.last().at, us(t0 + 2000 / v));
  CHECK(c.until(MotionEventKind::SwitchChanged));
  CHECK(!c.last().active && c.last().position == 4000);
  CHECK_EQ(c.last().at, us(t0 + 3000 / v));
  c.core->rotate(0, -1000);  // and back: closed at 3999, open at 2999
  CHECK(c.until(MotionEventKind::SwitchChanged));
  CHECK(c.last().active && c.last().position == 3999);
  CHECK(c.until(MotionEventKind::SwitchChanged));
  CHECK(!c.last().active && c.last().position == 2999);
}

// ---------------------------------------------------------------- reference search

namespace {

// Hard stops (149 = 0), minimum speed 0, the defaults otherwise: search speed 1000 units (194 = 0:
// as 4), switch speed 250 (195 = 0: 4 / 4), a_max 1000, pulse divisor 3, ramp divisor 7.
struct Search : mt::Searching<Chip> {
  explicit Search(int mode) : Searching(1000 * vunit(3), 250 * vunit(3), 1000 * aunit(3, 7)) {
    set(130, 0);
    set(193, mode);
  }
};

}  // namespace

TEST(rfs_mode1_left_stop_switch) {
  Search b(1);
  b.left_at(-20000);
  b.right_at(30000);
  b.start();
  b.one_edge(20000);
  CHECK_EQ(b.get(11), 1);
  CHECK_EQ(b.get(9), 1);
  CHECK_EQ(b.get(10), 0);
  CHECK_EQ(b.edge_moving(100), 1);  // the switch is at the reference point
}

TEST(rfs_mode2_right_then_left) {
  Search b(2);
  b.between_end_switches(30000);
  CHECK_EQ(b.get(11), 1);
  CHECK_EQ(b.get(10), 0);
}

TEST(rfs_mode3_right_then_reference_switch_from_both_sides) {
  Search b(3);
  b.left_at(-20000);
  b.right_at(30000);
  b.place(SwitchInput::Home, -150, 150);
  b.start();
  b.run(30000, true);  // right switch
  b.through(29850, 300);
  CHECK_EQ(b.get(196), 30000);
  CHECK_EQ(b.get(9), 1);  // the reference input: the home switch
  CHECK_EQ(b.get(11), 0);
  CHECK_EQ(b.edge_moving(1000), 151);
}

// 196 is "the distance between the end switches" (TMCM-1110 manual, 5.3): with a left stop
// switch at one position its middle is that position (docs/errata.md, "196 after mode 3").
TEST(rfs_mode3_tmc429_distance_between_the_end_switches) {
  Search b(3);
  b.between_end_switches(30000);
  CHECK_EQ(b.get(11), 1);
}

// 138 has no "hold" mode in any manual (0 position, 1 soft, 2 velocity): every TMC429 profile's
// range is 0..2 and the core refuses 3 (docs/errata.md, "Ramp mode 138 'hold'").
TEST(tmc429_ramp_mode_has_no_hold) {
  for (const char* name : {"tmcm-1110", "tmcm-3110", "tmcm-6110", "tmcm-351"}) {
    const tmcl::Profile* p = tmcl::find_profile(name);
    CHECK(p != nullptr && p->axis_param(138) != nullptr);
    if (!p || !p->axis_param(138)) continue;
    CHECK_EQ(p->axis_param(138)->max, 2);
    Bench m("tmc429", name, 1);
    CHECK(m.core->set_param(0, 138, 3) == tmcl::ParamWrite::OutOfRange);
    CHECK(m.core->set_param(0, 138, 2) == tmcl::ParamWrite::Ok);
  }
  Chip b;  // generic: the TMCM-1110's row
  CHECK(b.core->set_param(0, 138, 3) == tmcl::ParamWrite::OutOfRange);
  CHECK_EQ(b.get(138), 0);
}

TEST(rfs_mode4_left_switch_from_both_sides) {
  Search b(4);
  b.place(SwitchInput::StopLeft, -20300, -20000);  // a cam on the left input
  b.start();
  b.through(20000, 300);
  CHECK_EQ(b.get(11), 1);
  CHECK_EQ(b.edge_moving(1000), 151);
  Search c(4);  // a stop switch has one edge: its reference point is that edge
  c.left_at(-20000);
  c.start();
  c.one_edge(20000);
  CHECK_EQ(c.edge_moving(1000), 1);
}

// Mode 5 searches in -, mode 6 in +: the end switch on the way turns the search around.
TEST(rfs_modes5_and_6_home_switch_turning_at_the_end_switch) {
  for (int mode : {5, 6}) mt::home_turning_at_the_end_switch<Search>(mode);
}

TEST(rfs_modes7_and_8_home_switch_ignoring_end_switches) {
  for (int mode : {7, 8}) mt::home_ignoring_end_switches<Search>(mode);
}

TEST(rfs_plus_128_reverses_the_home_switch) {
  Search b(8 + 128);
  b.place(SwitchInput::Home, -150, 150);  // inverted: "closed" outside the range
  b.start();
  b.run(151, true);  // leaves the range at -151
  b.run(1, false);   // back into it at -150
  b.run(1, false);   // out again: one edge, the reference point -150
  b.move(1);
  b.done();
  CHECK_EQ(b.edge_moving(-1000), -1);
}

TEST(rfs_with_soft_stops_ends_on_the_reference_point) {
  for (int mode : {1, 3, 7}) {
    Search b(mode);
    b.set(149, 1);
    b.ends_on_the_reference_point();
    if (mode == 1) CHECK_EQ(b.edge_moving(100), 1);
    if (mode != 1) CHECK_EQ(b.edge_moving(-1000), -151);
  }
}

TEST(rfs_that_never_meets_its_switch_runs_until_stopped) {
  Search b(1);
  b.start();
  CHECK_EQ(b.core->next_event(), tmcl::kNever);  // no switch: nothing ends the search
  b.to(10000000);
  CHECK(b.core->position(0) < -200000);
  CHECK_EQ(b.core->reference_search(0, tmcl::RfsAction::Status), 1);
  b.core->reference_search(0, tmcl::RfsAction::Stop);
  CHECK(b.core->reference_done(0));
  CHECK_EQ(b.core->reference_search(0, tmcl::RfsAction::Status), 0);
  CHECK(b.until(MotionEventKind::Stopped));
  CHECK(b.core->position(0) < -200000);  // not referenced: the register is not zeroed
  CHECK_EQ(b.count(MotionEventKind::ReferenceDone), 0);
}

TEST(rfs_driven_by_timed_switches) {
  Search b(1);
  b.start();
  b.to(500000);
  const std::int32_t hit = b.core->position(0);
  b.core->set_switch(0, SwitchInput::StopLeft, true);  // stops hard where it is
  b.to(600000);
  CHECK(b.core->position(0) > hit);  // leaving it slowly
  b.core->set_switch(0, SwitchInput::StopLeft, false);
  const std::int32_t release = b.core->position(0);
  b.to(700000);
  const std::int32_t reenter = b.core->position(0);
  CHECK(reenter < release);
  b.core->set_switch(0, SwitchInput::StopLeft, true);
  // The centre of the two switching points (rounded down) is position 0 from now on.
  const std::int32_t ref = static_cast<std::int32_t>(std::floor((release + reenter) / 2.0));
  CHECK_EQ(b.core->position(0), reenter - ref);
  CHECK(b.until(MotionEventKind::ReferenceDone));
  CHECK_EQ(b.core->position(0), 0);
  CHECK(!b.core->reference_search(0, tmcl::RfsAction::Status));
}

TEST(rfs_is_aborted_by_a_motion_command) {
  Search b(1);
  b.left_at(-20000);
  b.start();
  b.to(200000);
  b.core->move_absolute(0, 0);
  CHECK(b.core->reference_done(0));
  CHECK(b.until(MotionEventKind::TargetReached));
  CHECK_EQ(b.core->position(0), 0);
  CHECK_EQ(b.count(MotionEventKind::ReferenceDone), 0);
}

TEST(tmc429_clone_keeps_the_search) {
  Search b(1);
  b.left_at(-20000);
  b.start();
  b.to(100000);
  auto copy = b.core->clone();
  CHECK(copy != nullptr);
  CHECK(!copy->reference_done(0));
  std::vector<tmcl::MotionEvent> ev;
  for (int i = 0; i < 20 && !copy->reference_done(0); ++i) copy->advance(copy->next_event(), ev);
  CHECK(copy->reference_done(0));
  CHECK_EQ(copy->position(0), 0);
}

// A switch change whose exact instant lies within the nanosecond after a whole microsecond is
// reported at that microsecond; the next scan starts past it (it looped for ever, found by
// fuzz_vm: leaving the home range at 2992 steps at 7812.5 pps with a_max 2047).
TEST(tmc429_switch_change_within_the_rounding_nanosecond) {
  Chip b;
  b.set(5, 2047);
  b.place(SwitchInput::Home, 0, 2991);
  b.core->rotate(0, 256);
  CHECK(b.until(MotionEventKind::SwitchChanged));
  CHECK(b.last().active && b.last().at == 0);  // it stands in the range: closed from the start
  CHECK(b.until(MotionEventKind::SwitchChanged));
  CHECK(!b.last().active);
  CHECK_EQ(b.last().position, 2992);
  CHECK_EQ(b.last().at, 387094 - 20);  // (the fuzz case's ROR took effect at 20 us)
  CHECK_EQ(b.core->next_event(), tmcl::kNever);
}

TEST(tmc429_a_parameter_written_while_cruising_reports_no_second_velocity_reached) {
  Chip b;
  mt::cruise_reports_velocity_reached_once(b, 5, 1000, 500);
}
