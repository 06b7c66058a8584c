// The encoder of the TMCM cores (tmc429, tmc5160; docs/motion.md, "Shaft and encoder") through
// the MotionCore API: 209 counts the shaft through the prescaler 210 (TMCM-1110 manual 5.4.1),
// a slip moves the shaft and not the counter, the deviation beyond 212 stops the motor at the
// exact step with its flag in 207, writing 209 re-aligns, a reference search keeps the deviation,
// and which profiles declare an encoder.
#include <utility>

#include "check.hpp"
#include "helpers.hpp"

using tmcl::MotionEventKind;

namespace {

// A TMCM-1110 (tmc429) with plain settings in its units; nothing trips by itself.
struct Tmc429 : mt::SwitchBench {
  Tmc429() : SwitchBench("tmc429", "tmcm-1110", 1) {
    for (auto [param, value] : {std::pair{154, 3}, {153, 7}, {4, 1000}, {5, 1000}, {130, 1}, {149, 0}, {12, 0}, {13, 0}})
      set(param, value);
  }
  void move(std::int32_t target) {
    core->move_absolute(0, target);
    CHECK(until(MotionEventKind::TargetReached));
  }
};

// A TMCM-1260 (tmc5160): A2 = D2 = 51200 pps², no SixPoint, hard stops at switches.
struct Tmc5160 : mt::SwitchBench {
  Tmc5160() : SwitchBench("tmc5160", "tmcm-1260", 1) {
    for (auto [param, value] : {std::pair{4, 51200}, {5, 51200}, {15, 0}, {16, 0}, {17, 51200}, {18, 51200}, {19, 0},
                                {20, 0}, {26, 0}, {12, 0}, {13, 0}, {193, 1}, {194, 51200}, {195, 5120}})
      set(param, value);
  }
};

}  // namespace

TEST(encoder_tmc429_counts_the_shaft_through_the_prescaler) {
  Tmc429 b;
  CHECK_EQ(b.get(210), 512);  // prescaler 1 at power-on (the profile's default)
  b.move(5000);
  CHECK_EQ(b.get(209), 5000);
  b.set(210, 1024);  // prescaler 2: the count goes on from 5000, two per microstep
  b.move(6000);
  CHECK_EQ(b.get(209), 7000);
  b.set(210, 256 + 4);  // prescaler 0.5; bit 2 selects a null-channel function, not the prescaler
  b.move(8000);
  CHECK_EQ(b.get(209), 8000);
  b.set(209, -5);  // writing 209 sets the count
  CHECK_EQ(b.get(209), -5);
  b.move(8010);
  CHECK_EQ(b.get(209), 0);
}

TEST(encoder_tmc429_slip_moves_the_shaft_not_the_counter) {
  Tmc429 b;
  b.move(10000);
  b.core->encoder_slip(0, -300);  // 212 = 0: no deviation check
  CHECK_EQ(b.core->position(0), 10000);
  CHECK_EQ(b.get(209), 9700);
  CHECK_EQ(b.core->next_event(), tmcl::kNever);
  b.move(12000);
  CHECK_EQ(b.get(209), 11700);  // the lost 300 stay lost
  b.set(1, 0);                  // SAP 1 moves the counter, not the shaft or its encoder
  CHECK_EQ(b.get(209), 11700);
}

TEST(encoder_tmc429_deviation_stops_at_the_first_step_beyond_212) {
  Tmc429 b;
  b.set(210, 1024);  // a mismatched prescaler: 209 = 2 * position, the deviation is -position
  b.set(212, 1000);
  b.core->move_absolute(0, 100000);
  CHECK(b.until(MotionEventKind::Deviation));
  CHECK_EQ(b.last().position, 1001);
  CHECK_EQ(b.core->position(0), 1001);
  CHECK_EQ(b.get(3), 0);  // stopped at once
  CHECK(!b.core->target_reached(0));
  CHECK_EQ(b.get(207), 2);  // 'deviation error'; reading does not clear it on the TMCM-1110
  CHECK_EQ(b.get(207), 2);
  b.set(209, 1001);  // re-aligned: the next move clears the flag and runs on
  b.set(210, 512);
  b.move(2000);
  CHECK_EQ(b.get(207), 0);
  CHECK_EQ(b.count(MotionEventKind::Deviation), 1);
}

TEST(encoder_tmc5160_slip_beyond_212_stops_a_moving_motor) {
  Tmc5160 b;
  b.set(212, 1000);
  b.core->rotate(0, 51200);
  b.to(1500000);
  const std::int32_t at = b.core->position(0);
  CHECK_EQ(b.get(209), at);  // the SensOstep count is in microsteps (manual 6.2)
  b.core->encoder_slip(0, -900);  // within 212: it runs on
  b.to(1600000);
  CHECK_EQ(b.count(MotionEventKind::Deviation), 0);
  CHECK(b.get(3) > 0);
  b.core->encoder_slip(0, -200);  // 1100 now
  CHECK_EQ(b.next(), 1600000);
  CHECK(b.last().kind == MotionEventKind::Deviation);
  CHECK_EQ(b.get(3), 0);
  CHECK_EQ(b.get(209), b.core->position(0) - 1100);
  CHECK_EQ(b.get(207), 2);  // 'deviation error', cleared by reading it (manual, 207)
  CHECK_EQ(b.get(207), 0);
  b.to(2000000);
  CHECK_EQ(b.count(MotionEventKind::Deviation), 1);
}

TEST(encoder_tmc5160_slip_at_rest_beyond_212_reports_at_once) {
  Tmc5160 b;
  b.set(212, 100);
  b.to(1000);
  b.core->encoder_slip(0, 150);
  CHECK_EQ(b.next(), 1000);
  CHECK(b.last().kind == MotionEventKind::Deviation);
  b.core->move_absolute(0, 5000);  // still 150 apart: the move stops where it starts
  CHECK(b.until(MotionEventKind::Deviation));
  CHECK_EQ(b.core->position(0), 0);
  b.set(209, 0);  // re-aligned
  b.core->move_absolute(0, 5000);
  CHECK(b.until(MotionEventKind::TargetReached));
  CHECK_EQ(b.get(209), 5000);
}

TEST(encoder_tmc5160_reference_search_keeps_the_deviation) {
  Tmc5160 b;
  b.left_at(-20000);
  b.core->encoder_slip(0, -100);
  b.to(0);
  b.core->reference_search(0, tmcl::RfsAction::Start);
  CHECK(b.until(MotionEventKind::ReferenceDone));
  CHECK_EQ(b.core->position(0), 0);
  CHECK_EQ(b.get(209), -100);  // the count moved with the counter (docs/errata.md E68)
}

TEST(encoder_is_declared_by_the_profile) {
  auto has = [](const char* core, const char* profile) {
    return tmcl::make_motion_core(core)->models_encoder(*tmcl::find_profile(profile));
  };
  CHECK(has("tmc429", "tmcm-1110"));
  CHECK(has("tmc429", "tmcm-351"));
  CHECK(has("tmc429", "generic"));  // the TMCM-1110's, as its units
  CHECK(!has("tmc429", "tmcm-6110"));
  CHECK(has("tmc5160", "tmcm-1260"));
  CHECK(!has("linear", "tmc2300-eval"));
  CHECK(has("tmc4361", "usb-2-sd"));
  Tmc429 b;  // a core on a profile without the encoder keeps 209 as written and checks nothing
  b.core->reset(*tmcl::find_profile("tmcm-6110"), 1);
  b.set(212, 10);
  b.core->encoder_slip(0, -500);
  CHECK_EQ(b.core->next_event(), tmcl::kNever);
  CHECK_EQ(b.get(209), 0);
}
