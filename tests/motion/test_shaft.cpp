// The shaft model (vm/motion/shaft.hpp): the shaft apart from the counter, lost steps, holds,
// slips, the encoder's prescaler and the exact deviation trip step.
#include "check.hpp"
#include "shaft.hpp"

using tmcl::shaft::Deviation;
using tmcl::shaft::Encoder;
using tmcl::shaft::Shaft;

TEST(shaft_follows_until_steps_are_lost) {
  Shaft s;
  CHECK_EQ(s.at(1000), 1000);
  s.lose(300);  // the counter went 300 further than the shaft
  CHECK_EQ(s.at(1300), 1000);
  s.slip(-50);  // the shaft slipped back by itself
  CHECK_EQ(s.at(1300), 950);
}

TEST(held_shaft_stands_while_the_counter_runs) {
  Shaft s;
  s.hold(500);
  CHECK_EQ(s.at(500), 500);
  CHECK_EQ(s.at(4000), 500);  // driving into a hard stop: every step lost
  s.release(4000);
  CHECK_EQ(s.at(4000), 500);
  CHECK_EQ(s.at(3000), -500);  // backing off: it follows again, 3500 steps behind
  CHECK_EQ(s.follows(), 1);
}

TEST(encoder_counts_through_the_prescaler) {
  Encoder e;
  e.num = 256, e.den = 512;  // 210 = 256: prescaler 0.5 (TMCM-1110 manual 5.4.1)
  CHECK_EQ(e.read(1001), 500);
  CHECK_EQ(e.read(-1), -1);  // floor, not toward zero
  e.set(1001, 7);            // SAP 209
  CHECK_EQ(e.read(1001), 7);
  CHECK_EQ(e.read(1201), 107);
  e.rescale(1201, 1024, 512);  // prescaler 2 from here on, the count does not jump
  CHECK_EQ(e.read(1201), 107);
  CHECK_EQ(e.read(1211), 127);
}

TEST(deviation_trip_is_the_first_step_beyond_the_limit) {
  Deviation d;
  CHECK(!d.trip(0, 1, 100).has_value());  // prescaler 1, no loss: the deviation never grows
  d.shaft.hold(0);                         // blocked at 0: deviation = x
  CHECK_EQ(*d.trip(0, 1, 100), 101);
  CHECK_EQ(*d.trip(0, -1, 100), -101);
  d.shaft.release(0);
  d.enc.num = 1024, d.enc.den = 512;  // the encoder counts twice as fast: deviation = -x
  CHECK_EQ(*d.trip(10, 1, 100), 101);
  d.to_commanded = 1000;  // 209 = 2 * (x + 1000): deviation = -x - 2000, beyond already
  CHECK_EQ(*d.trip(10, 1, 100), 10);
  Deviation e;
  e.enc.num = 511, e.enc.den = 512;  // one count short per 512 steps
  for (std::int64_t x : {std::int64_t{0}, std::int64_t{-77}}) {
    const std::int64_t t = *e.trip(x, 1, 3);
    CHECK(e.at(t) > 3);
    CHECK(e.at(t - 1) <= 3);
  }
}
