// Rows of the conformance tables (docs/conformance/) that no other motion test pinned: the
// measured speeds of the tmc4361 core (USB-2-SD axis parameters 131, 132) and the microstep and
// full-step resolutions (140, 202) in its encoder relation, and the right limit switch's disable
// (12) of the TMC429 and TMC5160 modules.
#include <utility>

#include "check.hpp"
#include "helpers.hpp"

using mt::Bench;

TEST(tmc4361_measured_speeds_follow_the_motor) {
  Bench b;
  CHECK_EQ(b.get(131), 0);
  b.core->rotate(0, 51200);
  b.to(500000);  // halfway up the ramp
  CHECK_EQ(b.get(131), 25600);
  CHECK_EQ(b.get(132), 25600);
  b.next();  // at speed
  CHECK_EQ(b.get(131), 51200);
  CHECK_EQ(b.get(132), 51200);
  b.set(210, -51200);  // an encoder counting the other way measures the other sign
  CHECK_EQ(b.get(131), -51200);
}

TEST(tmc4361_encoder_counts_scale_with_microsteps_and_full_steps) {
  Bench b;
  b.set(140, 4);     // 16 microsteps
  b.set(210, 3200);  // 3200 counts per turn of 200 full steps: one count a microstep
  b.core->encoder_slip(0, 10);
  CHECK_EQ(b.get(209), 10);
  b.set(202, 400);  // 400 full steps a turn: two microsteps a count
  b.core->encoder_slip(0, 10);
  CHECK_EQ(b.get(209), 30);
}

// Axis parameter 12 on both cores with limit switches: the right switch stops a move into it
// (10 reads it), and with its stop function off (12 = 1) the motor passes it.
TEST(right_limit_switch_disable_lets_the_motor_pass) {
  for (const auto& [core, profile] : {std::pair{"tmc429", "tmcm-1110"}, std::pair{"tmc5160", "tmcm-1260"}}) {
    mt::SwitchBench stops(core, profile);
    stops.right_at(2000);
    stops.core->move_absolute(0, 5000);
    CHECK(stops.until(tmcl::MotionEventKind::Stopped));
    CHECK(stops.core->position(0) < 5000);
    CHECK_EQ(stops.get(10), 1);
    mt::SwitchBench passes(core, profile);
    passes.set(12, 1);
    passes.right_at(2000);
    passes.core->move_absolute(0, 5000);
    CHECK(passes.until(tmcl::MotionEventKind::TargetReached));
    CHECK_EQ(passes.core->position(0), 5000);
    CHECK_EQ(passes.get(10), 1);
  }
}
