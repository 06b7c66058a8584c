// Loads, stalls and lost steps on the TMCM cores (stall.hpp, stall_core.cpp; docs/motion.md,
// "Loads, stalls and lost steps"): the load value's model (monotone in the load, shifted by 174,
// 0 at the stall, measured at fullsteps or every fourth with the filter), stop on stall above and
// not below 181, hard stops with and without stop on stall.
#include <cmath>

#include "check.hpp"
#include "helpers.hpp"
#include "stall.hpp"

using tmcl::MotionEventKind;
using tmcl::SwitchInput;

using mt::Axis1260;  // rotating at 51200 pps = 200 fullsteps/s, 256 microsteps, scale 16

TEST(load_value_falls_with_the_load_and_rises_with_174) {
  Axis1260 b;
  b.wait(20000);
  CHECK_EQ(b.get(206), tmcl::stall::reading(200, 16, 0, 0));
  CHECK_EQ(b.get(206), 326);  // 250 + 500 · 17/32 · 200/700, rounded
  int last = 1024;
  for (int p : {0, 10, 30, 50, 70, 90, 99}) {
    b.load(p);
    b.wait(20000);
    const int v = b.get(206);
    CHECK(v < last);
    CHECK_EQ(v, tmcl::stall::reading(200, 16, p, 0));
    last = v;
  }
  b.load(100);
  b.wait(20000);
  CHECK_EQ(b.get(206), 0);  // at the stall
  CHECK_EQ(b.get(208) & 1, 1);
  // 174 shifts the reading by 8 per unit under the same load; raising it raises the reading.
  b.load(50);
  b.wait(20000);
  const int at0 = b.get(206);
  b.set(174, 5);
  b.wait(20000);
  CHECK_EQ(b.get(206), at0 + 40);
  b.set(174, -20);
  b.wait(20000);
  CHECK_EQ(b.get(206), std::max(0, at0 - 160));
  CHECK_EQ(b.get(208) & 1, at0 - 160 <= 0 ? 1 : 0);
}

// The run current (6) and the microstep resolution (140) are inputs of the load value a program
// reads (conformance rows 6 and 140, issue 41): the current scale in N(f, cs), the fullstep rate
// f = |v| / 2^140; and with them whether a load reads 0, a stall.
TEST(load_value_follows_the_run_current_and_the_microstep_resolution) {
  Axis1260 b;  // 6 = 128 (scale 16), 140 = 8: 51200 pps is 200 fullsteps/s
  b.wait(20000);
  CHECK_EQ(b.get(206), tmcl::stall::reading(200, 16, 0, 0));
  b.set(6, 255);  // scale 31
  b.wait(20000);
  CHECK_EQ(b.get(206), tmcl::stall::reading(200, 31, 0, 0));
  b.set(140, 6);  // 64 microsteps: 800 fullsteps/s
  b.wait(20000);
  CHECK_EQ(b.get(206), tmcl::stall::reading(800, 31, 0, 0));
  CHECK(tmcl::stall::reading(800, 31, 0, 0) != tmcl::stall::reading(200, 31, 0, 0));
  // 95 % with 174 = -2: the full current still reads above 0, a low one reads 0 (a stall).
  b.set(140, 8);
  b.set(174, -2);
  b.load(95);
  b.wait(20000);
  CHECK(b.get(206) > 0);
  b.set(6, 7);  // scale 0
  b.wait(20000);
  CHECK_EQ(b.get(206), 0);
  CHECK_EQ(b.get(208) & 1, 1);
}

// A new load shows at the next measurement: the first microsecond at which the counter has passed
// a fullstep (256 microsteps), or every fourth fullstep with the filter (173 = 1).
TEST(load_value_changes_only_at_measurements) {
  for (int filter : {0, 1}) {
    Axis1260 b;
    b.set(173, filter);
    b.wait(30000);
    const int before = b.get(206);
    b.load(60);
    CHECK_EQ(b.get(206), before);
    const std::int64_t P = filter ? 1024 : 256;
    const std::int64_t start = b.core->position(0);
    tmcl::SimTime t = b.now;
    while (b.get(206) == before) {
      b.to(++t);
      CHECK(t < b.now + 30000);
    }
    const std::int64_t at = b.core->position(0);
    CHECK(at % P == 0 || (at - 1) % P == 0 || at / P != (at - 1) / P);
    CHECK(at / P > start / P);                     // a measurement point was passed ...
    CHECK((b.core->sample_at(0, t - 1).position) / P == start / P);  // ... just now
    CHECK_EQ(b.get(206), tmcl::stall::reading(200, 16, 60, 0));
  }
}

// Stop on stall: a measurement reading 0 at a speed >= 181 stops the motor at once; below 181 it
// runs on, and the stalled shaft stands while the counter runs on (said once).
TEST(stop_on_stall_above_181_and_not_below) {
  {
    Axis1260 b;
    b.set(181, 40000);
    b.load(100);
    CHECK(b.until(MotionEventKind::Stall));
    CHECK_EQ(b.count(MotionEventKind::Stall), 1);
    CHECK(b.now - 0 > 0);
    CHECK_EQ(b.get(3), 0);  // stopped at once
    CHECK_EQ(b.get(206), 0);
    CHECK_EQ(b.get(208) & 1, 1);
    CHECK(b.core->position(0) % 256 == 0);  // at a measurement, a fullstep
    CHECK(b.next() == tmcl::kNever);
  }
  {
    Axis1260 b;
    b.set(181, 60000);  // above the speed: no stop
    b.load(100);
    CHECK(b.until(MotionEventKind::StepsLost));
    b.wait(1000000);
    CHECK_EQ(b.count(MotionEventKind::Stall), 0);
    CHECK_EQ(b.count(MotionEventKind::StepsLost), 1);
    CHECK_EQ(b.get(3), 51200);
    CHECK_EQ(b.get(206), 0);
  }
  {
    Axis1260 b;  // 181 = 0: off
    b.load(150);
    b.wait(1000000);
    CHECK_EQ(b.count(MotionEventKind::Stall), 0);
    CHECK_EQ(b.get(3), 51200);
  }
}

// A TMCM-1110 homing into a hard stop at -5000 (physical): with stop on stall the motor stops
// within a fullstep past the stop, once per push; without, the counter runs on (steps lost, said
// once) while the load value reads 0.
TEST(hard_stop_with_and_without_stop_on_stall) {
  auto axis = [] {
    mt::SwitchBench b("tmc429", "tmcm-1110", 1);
    b.set(140, 4);  // 16 microsteps: a fullstep is 16
    b.set(154, 3);
    b.set(153, 7);
    b.set(5, 1000);
    CHECK(b.core->place_hard_stop(0, SwitchInput::StopLeft, -5000));
    return b;
  };
  {
    auto b = axis();
    b.set(181, 100);
    b.core->rotate(0, -400);  // 12207 pps = 763 fullsteps/s
    CHECK(b.until(MotionEventKind::Stall, 20));
    CHECK_EQ(b.count(MotionEventKind::StepsLost), 0);
    const std::int32_t p = b.core->position(0);
    CHECK(p <= -5000 && p > -5000 - 16 - 1);
    CHECK_EQ(b.get(3), 0);
    CHECK_EQ(b.get(208) & 1, 1);
    CHECK(b.next() == tmcl::kNever);
    // Pushing again stalls again: one stall per push.
    b.core->rotate(0, -400);
    CHECK(b.until(MotionEventKind::Stall, 20));
    CHECK_EQ(b.count(MotionEventKind::Stall), 2);
    CHECK(b.core->position(0) >= p - 16 * 40);
    // Backing off is free: the shaft follows again.
    b.core->move_absolute(0, 0);
    CHECK(b.until(MotionEventKind::TargetReached, 20));
    CHECK_EQ(b.count(MotionEventKind::Stall), 2);
  }
  {
    auto b = axis();  // 181 = 0: no stop
    b.core->rotate(0, -400);
    CHECK(b.until(MotionEventKind::StepsLost, 20));
    CHECK(std::abs(b.core->position(0) + 5000) <= 1);
    b.to(b.now + 1000000);
    CHECK(b.core->position(0) < -5000 - 12000);  // the counter runs on
    CHECK_EQ(b.count(MotionEventKind::StepsLost), 1);
    CHECK_EQ(b.get(206), 0);
    // 174 high enough: the blocked rotor does not read 0 (less sensitive: "requires more torque").
    b.set(174, 10);
    b.to(b.now + 100000);
    CHECK_EQ(b.get(206), 80);
  }
  {
    auto b = axis();  // a stall too slow for 181 is no stop either
    b.set(181, 1000);
    b.core->rotate(0, -400);
    CHECK(b.until(MotionEventKind::StepsLost, 20));
    b.to(b.now + 1000000);
    CHECK_EQ(b.count(MotionEventKind::Stall), 0);
  }
}

// Without motion nothing is measured: the reading holds; a hard stop far away changes nothing.
TEST(load_value_holds_at_rest) {
  Axis1260 b;
  b.core->stop(0);
  CHECK(b.until(MotionEventKind::Stopped));
  const int v = b.get(206);  // measured last while slowing down, above the minimum speed
  CHECK(v > 250 && v < 326);
  b.load(80);
  b.wait(1000000);
  CHECK_EQ(b.get(206), v);
}

// A load between two positions: the reading falls inside the range only.
TEST(load_between_positions) {
  mt::SwitchBench b("tmc5160", "tmcm-1260", 1);
  b.set(140, 8);
  b.set(5, 1000000);
  CHECK(b.core->place_load(0, 100000, 200000, 80));
  b.core->rotate(0, 51200);
  b.to(1000000);  // at 51200 steps
  const int free = b.get(206);
  b.to(3000000);  // at ~153000: inside
  CHECK(b.get(206) < free);
  CHECK_EQ(b.get(206), tmcl::stall::reading(200, 16, 80, 0));
  b.to(5000000);  // past it
  CHECK_EQ(b.get(206), free);
}
