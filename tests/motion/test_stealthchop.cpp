// stallGuard2 in StealthChop on the TMCM-1260's TMC5160 (issue 41, 2; errata E78): the driver is
// in StealthChop below the PWM threshold speed 186 while the PWM gradient 187 > 0 (PD57/60-1260
// manual, 186 and 187) and measures no load there: 206 holds its last measurement, no stall stops
// the motor, coolStep does not regulate (180 is the run current); at or above 186, and with
// 187 = 0, stallGuard2 works as before.
#include "check.hpp"
#include "helpers.hpp"
#include "stall.hpp"

using tmcl::MotionEventKind;
using tmcl::SwitchInput;

// Each test: a TMCM-1260 at 256 microsteps and scale 16 (mt::Axis1260), set up first and then
// rotated at 51200 pps (200 fullsteps/s).

TEST(stealthchop_measures_no_load) {
  mt::Axis1260 b(false);
  b.cruise();
  b.wait(20000);
  const int free = b.get(206);
  CHECK_EQ(free, tmcl::stall::reading(200, 16, 0, 0));
  b.set(186, 100000);  // StealthChop below 100000 pps: 51200 is in it once 187 > 0
  b.set(187, 5);
  b.load(60);
  b.wait(200000);
  CHECK_EQ(b.get(206), free);  // holds: no measurement in StealthChop
  b.set(186, 51200);           // at the threshold the driver is in SpreadCycle ("below this value")
  b.wait(20000);
  CHECK_EQ(b.get(206), tmcl::stall::reading(200, 16, 60, 0));
  b.set(186, 100000);
  b.load(0);
  b.wait(20000);
  CHECK_EQ(b.get(206), tmcl::stall::reading(200, 16, 60, 0));
  b.set(187, 0);  // StealthChop off: measured again
  b.wait(20000);
  CHECK_EQ(b.get(206), free);
}

// A stall homing in StealthChop stops nothing: the shaft meets the hard stop and steps are lost;
// the same run in SpreadCycle stops on the stall within a fullstep.
TEST(stealthchop_stops_on_no_stall) {
  for (int stealth = 0; stealth < 2; ++stealth) {
    mt::Axis1260 b(false);
    CHECK(b.core->place_hard_stop(0, SwitchInput::StopRight, 100000));
    b.set(181, 1);
    b.set(186, 100000);
    b.set(187, stealth ? 5 : 0);
    b.cruise();
    CHECK(b.until(stealth ? MotionEventKind::StepsLost : MotionEventKind::Stall));
    b.wait(1000000);
    CHECK_EQ(b.count(MotionEventKind::Stall), 1 - stealth);
    if (stealth)
      CHECK(b.core->position(0) > 140000);  // the counter ran on
    else
      CHECK(b.core->position(0) <= 100000 + 256 + 1);
  }
}

// coolStep does not regulate in StealthChop: 180 stays the run current under a light load that
// lowers it in SpreadCycle.
TEST(stealthchop_coolstep_does_not_regulate) {
  for (int stealth = 0; stealth < 2; ++stealth) {
    mt::Axis1260 b(false);
    b.set(172, 1);  // coolStep on: lower threshold 32, upper 64
    b.set(169, 3);  // a step down after each reading above the upper threshold
    b.set(186, 100000);
    b.set(187, stealth ? 5 : 0);
    b.cruise();
    b.wait(500000);
    if (stealth)
      CHECK_EQ(b.get(180), 16);
    else
      CHECK(b.get(180) < 16);
  }
}
