// The linear core (TMC2300-MOTOR-EVAL): one acceleration both ways, speeds clipped to ±32767.
#include "check.hpp"
#include "helpers.hpp"

using mt::Bench;
using tmcl::MotionEventKind;

TEST(linear_positioning) {
  Bench b("linear", "tmc2300-eval");
  b.core->move_absolute(0, 100000);  // V = A = 10000: 1 s up, 9 s cruise, 1 s down
  CHECK_EQ(b.next(), 11000000);
  CHECK_EQ(b.core->position(0), 100000);
  CHECK(b.last().kind == MotionEventKind::TargetReached);
}

TEST(linear_short_move) {
  Bench b("linear", "tmc2300-eval");
  b.core->move_absolute(0, -2500);  // 2 sqrt(D/A) = 1 s
  CHECK_EQ(b.next(), 1000000);
  CHECK_EQ(b.core->position(0), -2500);
}

TEST(linear_velocity_clip_and_currents) {
  Bench b("linear", "tmc2300-eval");
  CHECK_EQ(b.get(180), 8);
  b.core->rotate(0, 40000);
  CHECK_EQ(b.get(2), 32767);
  CHECK_EQ(b.next(), 3276700);
  CHECK_EQ(b.get(3), 32767);
  CHECK_EQ(b.get(180), 16);
  b.core->rotate(0, -32767);  // reversal: down and up with the same acceleration
  CHECK_EQ(b.next(), 3276700 + 2 * 3276700);
  b.core->stop(0);
  b.next();
  CHECK(b.last().kind == MotionEventKind::Stopped);
  CHECK_EQ(b.get(180), 8);
}

TEST(linear_ignores_switches) {
  Bench b("linear", "tmc2300-eval");
  b.core->move_absolute(0, 1000);
  b.core->set_switch(0, tmcl::SwitchInput::StopRight, true);
  b.next();
  CHECK(b.last().kind == MotionEventKind::TargetReached);
}

TEST(linear_mid_move_change) {
  Bench b("linear", "tmc2300-eval");
  b.core->move_absolute(0, 100000);
  b.to(1000000);
  b.set(5, 5000);  // decel now 2 s, 10000 steps: cruise 100000 - 5000 - 10000 = 85000
  CHECK_EQ(b.next(), 1000000 + 8500000 + 2000000);
}
