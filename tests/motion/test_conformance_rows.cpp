// Rows of the conformance tables (docs/conformance/) that no other motion test pinned: the
// measured speeds of the tmc4361 core (USB-2-SD axis parameters 131, 132) and the microstep and
// full-step resolutions (140, 202) in its encoder relation.
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
