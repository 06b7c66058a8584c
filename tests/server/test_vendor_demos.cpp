// The vendor's example scripts for the TMCM-3351 and TMCM-3312 (PyTrinamic
// examples/modules/TMCM3351/TMCL/rotate_demo.py and TMCM3312/TMCL/rotate_demo.py, identical but
// for the module's name) against `tmclrun --serve -t MODULE`: the requests the script sends
// through PyTrinamic's TMCM3351/TMCM3312 classes, in its order, each answered with status 100 as a
// module answers them (PyTrinamic raises on any other status). PyTrinamic is not a dependency of
// the tests, so its requests are replayed here as its classes make them: drive settings (the
// class has no MaxCurrent, so max_current sends nothing; standby 7, boost 200, microsteps 140, read
// back when printed), ramp settings (4, 5), actual position 1 := 0, ROR of each motor (motor 1
// negative), MST after five seconds, the positions, MVP REL by the position, polling 8/0/1 until
// every motor reached its target, MVP ABS 0 and polling again. Simulated time runs 20 times the
// wall clock, so the script's five-second rotation takes a quarter of a second.
#include "check.hpp"
#include "child.hpp"

using namespace srvtest;

namespace {

// The script's loop: "while not all three reached: print target and actual position of each".
void poll_until_reached(Link& l) {
  for (int round = 0; round < 2000; ++round) {
    bool all = true;
    for (std::uint8_t m = 0; m < 3; ++m) all = ask(l, kGap, 8, m, 0) != 0 && all;
    if (all) return;
    for (std::uint8_t m = 0; m < 3; ++m) ask(l, kGap, 0, m, 0), ask(l, kGap, 1, m, 0);
    sleep_ms(10);
  }
  ::tmcl_test::fail(__FILE__, __LINE__, "the motors never all reached their targets");
}

void rotate_demo(const char* module) {
  Child c = spawn_tmclrun({"-t", module, "--serve", "tcp:127.0.0.1:0", "--time-scale", "20", "--max-wall-time", "60s"});
  CHECK(c.line.rfind("listening on 127.0.0.1:", 0) == 0);
  {
    Link l = connect_to(c.line);
    CHECK(l.ok());
    // Preparing parameters: drive settings of each motor, printed.
    for (std::uint8_t m = 0; m < 3; ++m) {
      ask(l, kSap, 7, m, 0);    // standby_current = 0
      ask(l, kSap, 200, m, 0);  // boost_current = 0
      ask(l, kSap, 140, m, 8);  // microstep_resolution = 256 microsteps
      CHECK_EQ(ask(l, kGap, 200, m, 0), 0);
      CHECK_EQ(ask(l, kGap, 140, m, 0), 8);
    }
    // Ramp settings, actual position 0, printed.
    const std::int32_t accel[] = {51200, 25600, 102400}, vmax[] = {51200, 25600, 51200};
    for (std::uint8_t m = 0; m < 3; ++m) {
      ask(l, kSap, 5, m, accel[m]);
      ask(l, kSap, 4, m, vmax[m]);
    }
    for (std::uint8_t m = 0; m < 3; ++m) ask(l, kSap, 1, m, 0);
    for (std::uint8_t m = 0; m < 3; ++m) {
      CHECK_EQ(ask(l, kGap, 4, m, 0), vmax[m]);
      CHECK_EQ(ask(l, kGap, 5, m, 0), accel[m]);
    }
    // Rotating (PyTrinamic's rotate sends ROR with the signed speed), stopping after 5 s.
    const std::int32_t speed[] = {51200, -25600, 102400};
    for (std::uint8_t m = 0; m < 3; ++m) ask(l, kRor, 0, m, speed[m]);
    sleep_ms(250);
    for (std::uint8_t m = 0; m < 3; ++m) ask(l, kMst, 0, m, 0);
    std::int32_t pos[3];
    for (std::uint8_t m = 0; m < 3; ++m) pos[m] = ask(l, kGap, 1, m, 0);
    CHECK(pos[0] > 51200 && pos[1] < -25600 && pos[2] > 102400);  // each turned its way for seconds
    sleep_ms(100);
    for (std::uint8_t m = 0; m < 3; ++m) pos[m] = ask(l, kGap, 1, m, 0);  // at rest after the stop ramps
    // Doubling moved distance: MVP REL by the actual position.
    for (std::uint8_t m = 0; m < 3; ++m) ask(l, kMvp, 1, m, ask(l, kGap, 1, m, 0));
    poll_until_reached(l);
    // 127 = 0 (the default): MVP REL counts from the last target, which ROR left at 0, so each
    // motor goes to its own position and stays (docs/profiles.md, TMCM-3312 and TMCM-3351).
    for (std::uint8_t m = 0; m < 3; ++m) CHECK_EQ(ask(l, kGap, 1, m, 0), pos[m]);
    // Moving back to 0.
    for (std::uint8_t m = 0; m < 3; ++m) ask(l, kMvp, 0, m, 0);
    poll_until_reached(l);
    for (std::uint8_t m = 0; m < 3; ++m) CHECK_EQ(ask(l, kGap, 1, m, 0), 0);
  }
  ::kill(c.pid, SIGTERM);
  CHECK_EQ(reap(c), 0);
}

}  // namespace

TEST(vendor_rotate_demo_runs_on_the_tmcm3351) { rotate_demo("tmcm-3351"); }
TEST(vendor_rotate_demo_runs_on_the_tmcm3312) { rotate_demo("tmcm-3312"); }
