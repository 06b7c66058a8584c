// The tmc5160 core (TMCM-1260, PD57/60-1260 manual 1.44) through its public API: its rows and
// ranges from the module's profile, SixPoint move times against the closed form (sections 1.3,
// 7.5), velocity mode on A2 alone, moves into the limit switches (hard, soft, disabled), and
// every mode of the reference search, +64 and +128 included (section 7.1, table 20).
#include <cmath>
#include <random>
#include <utility>

#include "check.hpp"
#include "helpers.hpp"

using mt::near;
using mt::us;
using tmcl::MotionEventKind;
using tmcl::ParamWrite;
using tmcl::SwitchInput;

namespace {

// The TMCM-1260 with plain settings: SixPoint off (V1 = 0), no start or stop speed, hard stops,
// both stop functions on, A2 = D2 = 51200 pps², search 51200 pps, switch speed 5120 pps.
struct Drive : mt::SwitchBench {
  Drive() : SwitchBench("tmc5160", "tmcm-1260", 1) {
    for (auto [param, value] : {std::pair{4, 51200}, {5, 51200}, {15, 0}, {16, 0}, {17, 51200}, {18, 51200},
                                {19, 0}, {20, 0}, {26, 0}, {12, 0}, {13, 0}, {193, 1}, {194, 51200}, {195, 5120}})
      set(param, value);
  }
  // The SixPoint ramp of the tests below.
  void sixpoint(int vstart, int a1, int v1, int a2, int vmax, int d2, int d1, int vstop) {
    for (auto [param, value] : {std::pair{19, vstart}, {15, a1}, {16, v1}, {5, a2}, {4, vmax}, {17, d2}, {18, d1}, {20, vstop}})
      set(param, value);
  }
};

struct PpsSearch : mt::Searching<Drive> {
  explicit PpsSearch(int mode) : Searching(51200, 5120, 51200) { set(193, mode); }
};

}  // namespace

TEST(tmc5160_is_the_tmcm1260s_core_with_its_rows_and_ranges) {
  const tmcl::Profile* p = tmcl::find_profile("tmcm-1260");
  CHECK(p != nullptr);
  CHECK(p->default_motion == "tmc5160");
  mt::Bench d("tmc5160", "tmcm-1260", 1);
  CHECK_EQ(d.get(4), p->axis_param(4)->default_value);
  CHECK_EQ(d.get(20), p->axis_param(20)->default_value);
  CHECK_EQ(d.get(193), p->axis_param(193)->default_value);
  CHECK(!d.core->physical(0, 4, 1000));  // pps already: no chip units
  CHECK(d.core->units_note().empty());
  // 193: modes 1-8, +64 with 1-4 (the other end switch), +128 with 5-8 (the home switch inverted).
  for (int v : {1, 2, 3, 4, 5, 6, 7, 8, 65, 66, 67, 68, 133, 134, 135, 136})
    CHECK(d.core->set_param(0, 193, v) == ParamWrite::Ok);
  for (int v : {0, 9, 64, 69, 72, 129, 132, 137, 192, 200, -1})
    CHECK(d.core->set_param(0, 193, v) == ParamWrite::OutOfRange);
  for (int ro : {3, 8, 9, 10, 11, 196, 197}) CHECK(d.core->set_param(0, ro, 0) == ParamWrite::ReadOnly);
  CHECK(d.core->set_param(0, 16, 1000001) == ParamWrite::OutOfRange);  // V1: 0..1000000
  CHECK(d.core->set_param(0, 19, 250000) == ParamWrite::OutOfRange);   // VSTART: 0..249999
  d.core->rotate(0, 9000000);  // the register's bound: parameter 2's range
  CHECK_EQ(d.get(2), 7999774);
}

// Section 1.3: from VSTART with A1 to V1, with A2 to VMAX; down with D2 to V1, with D1 to VSTOP,
// then at rest on the target. Reaching VMAX and not, and V1 = 0 (A2 and D2 alone).
TEST(tmc5160_sixpoint_move_times_match_the_closed_form) {
  const double vs = 1000, a1 = 100000, v1 = 20000, a2 = 50000, vmax = 60000, d2 = 40000, d1 = 80000, ve = 2000;
  {
    Drive b;
    b.sixpoint(1000, 100000, 20000, 50000, 60000, 40000, 80000, 2000);
    const double dist = 200000;
    const double ta = (v1 - vs) / a1 + (vmax - v1) / a2, sa = (v1 * v1 - vs * vs) / (2 * a1) + (vmax * vmax - v1 * v1) / (2 * a2);
    const double td = (vmax - v1) / d2 + (v1 - ve) / d1, sd = (vmax * vmax - v1 * v1) / (2 * d2) + (v1 * v1 - ve * ve) / (2 * d1);
    const double total = ta + (dist - sa - sd) / vmax + td;
    b.core->move_absolute(0, 200000);
    auto v_at = [&](double t) { return b.core->sample_at(0, static_cast<tmcl::SimTime>(std::llround(t * 1e6))).velocity; };
    CHECK(near(v_at(0.1), vs + a1 * 0.1, 0, 1));                     // A1 phase
    CHECK(near(v_at(0.19 + 0.4), v1 + a2 * 0.4, 0, 1));              // A2 phase
    CHECK(near(v_at(ta + 0.1), vmax, 0, 1e-6));                       // cruise
    CHECK(near(v_at(total - td + 0.5), vmax - d2 * 0.5, 0, 1));      // D2 phase
    CHECK(near(v_at(total - 0.1), ve + d1 * 0.1, 0, 1));             // D1 phase
    CHECK_EQ(b.next(), us(total));
    CHECK(b.last().kind == MotionEventKind::TargetReached);
    CHECK_EQ(b.core->position(0), 200000);
    CHECK_EQ(b.get(8), 1);
  }
  {  // a short move peaks below VMAX: (vp² - V1²)(1/2A2 + 1/2D2) covers what the V1 legs leave
    Drive b;
    b.sixpoint(1000, 100000, 20000, 50000, 60000, 40000, 80000, 2000);
    const double dist = 30000;
    const double s1 = (v1 * v1 - vs * vs) / (2 * a1) + (v1 * v1 - ve * ve) / (2 * d1);
    const double vp = std::sqrt(v1 * v1 + (dist - s1) / (1 / (2 * a2) + 1 / (2 * d2)));
    CHECK(vp < vmax);
    const double total = (v1 - vs) / a1 + (vp - v1) / a2 + (vp - v1) / d2 + (v1 - ve) / d1;
    b.core->move_absolute(0, 30000);
    CHECK_EQ(b.next(), us(total));
    CHECK_EQ(b.core->position(0), 30000);
  }
  {  // V1 = 0: A1 and D1 are not used, however small (manual, parameter 16)
    Drive b;
    b.sixpoint(1000, 1, 0, 50000, 60000, 40000, 1, 2000);
    const double dist = 200000;
    const double sa = (vmax * vmax - vs * vs) / (2 * a2), sd = (vmax * vmax - ve * ve) / (2 * d2);
    const double total = (vmax - vs) / a2 + (dist - sa - sd) / vmax + (vmax - ve) / d2;
    b.core->move_absolute(0, -200000);
    CHECK_EQ(b.next(), us(total));
    CHECK_EQ(b.core->position(0), -200000);
  }
}

// Section 7.5's note: velocity mode ramps with A2 (5) alone; A1, V1, D1, D2 and the start speed
// have no part in it, and MST stops with A2 too.
TEST(tmc5160_velocity_mode_uses_a2_both_ways) {
  Drive b;
  b.sixpoint(5000, 1000, 20000, 50000, 60000, 1000, 1000, 5000);
  b.core->rotate(0, 30000);
  CHECK_EQ(b.next(), us(30000.0 / 50000));
  CHECK(b.last().kind == MotionEventKind::VelocityReached);
  CHECK_EQ(b.get(2), 30000);
  CHECK_EQ(b.get(3), 30000);
  const tmcl::SimTime t0 = b.now + 100000;
  b.to(t0);
  b.core->stop(0);
  CHECK_EQ(b.next(), t0 + us(30000.0 / 50000));
  CHECK(b.last().kind == MotionEventKind::Stopped);
  CHECK_EQ(b.get(3), 0);
}

// A move into a limit switch: stopped at the switch (26 = 0) or with the ramp beyond it (26 = 1),
// not at all with its stop function off (13 = 1); 9, 10, 11 read the switches.
TEST(tmc5160_moves_into_a_limit_switch) {
  const double v = 20000, a = 51200;
  {
    Drive b;
    b.left_at(-20000);
    b.core->rotate(0, -20000);
    CHECK(b.until(MotionEventKind::Stopped));
    CHECK_EQ(b.core->position(0), -20000);
    CHECK_EQ(b.now, us(mt::run_time(20000, v, a)));
    CHECK_EQ(b.get(11), 1);
    CHECK_EQ(b.get(10), 0);
    CHECK_EQ(b.get(9), 0);
    CHECK_EQ(b.get(3), 0);
    b.core->rotate(0, -20000);  // further in: it does not move
    b.to(b.now + 100000);
    CHECK_EQ(b.core->position(0), -20000);
    b.core->rotate(0, 20000);  // away from it: free
    CHECK(b.until(MotionEventKind::VelocityReached));
    CHECK(b.core->position(0) > -20000);
  }
  {
    Drive b;
    b.set(26, 1);
    b.left_at(-20000);
    b.core->rotate(0, -20000);
    CHECK(b.until(MotionEventKind::Stopped));
    CHECK_EQ(b.core->position(0), -20000 - static_cast<std::int32_t>(std::floor(v * v / (2 * a))));
    CHECK_EQ(b.get(11), 1);
  }
  {
    Drive b;
    b.set(13, 1);
    b.left_at(-20000);
    b.core->rotate(0, -20000);
    CHECK(b.until(MotionEventKind::VelocityReached));
    b.to(b.now + 2000000);
    CHECK(b.core->position(0) < -30000);
    CHECK_EQ(b.get(11), 1);
    CHECK_EQ(b.count(MotionEventKind::Stopped), 0);
  }
  {  // a positioning through the right switch stops at it; the target is not reached
    Drive b;
    b.right_at(30000);
    b.core->move_absolute(0, 50000);
    CHECK(b.until(MotionEventKind::Stopped));
    CHECK_EQ(b.core->position(0), 30000);
    CHECK_EQ(b.get(10), 1);
    CHECK_EQ(b.get(8), 0);
    CHECK_EQ(b.count(MotionEventKind::TargetReached), 0);
  }
}

// ---------------------------------------------------------------- reference search (7.1)

TEST(tmc5160_rfs_modes_1_and_65_one_end_switch) {
  PpsSearch b(1);
  b.left_at(-20000);
  b.right_at(30000);
  b.start();
  b.one_edge(20000);
  CHECK_EQ(b.get(11), 1);
  CHECK_EQ(b.get(10), 0);
  CHECK_EQ(b.get(197), -20000);  // where the reference point was before it became 0
  CHECK_EQ(b.edge_moving(100), 1);
  PpsSearch c(65);  // +64: the right switch instead
  c.left_at(-20000);
  c.right_at(30000);
  c.start();
  c.one_edge(30000);
  CHECK_EQ(c.get(10), 1);
  CHECK_EQ(c.get(11), 0);
  CHECK_EQ(c.get(197), 30000);
  CHECK_EQ(c.edge_moving(-100), -1);
}

// 196: the distance between the two end switches (7.1.2).
TEST(tmc5160_rfs_modes_2_and_66_both_end_switches) {
  PpsSearch b(2);
  b.between_end_switches(30000);
  CHECK_EQ(b.get(11), 1);
  CHECK_EQ(b.get(10), 0);
  PpsSearch c(66);  // +64: the left one first, the right one is the zero point
  c.between_end_switches(20000);
  CHECK_EQ(c.get(10), 1);
  CHECK_EQ(c.get(11), 0);
  CHECK_EQ(c.edge_moving(-100), -1);
}

// 196: "the distance between the right end switch and the middle of the left end switch"
// (7.1.3). Mode 3 searches the left stop switch, not the home switch (its own input here).
TEST(tmc5160_rfs_modes_3_and_67_the_zero_switch_from_both_sides) {
  PpsSearch b(3);
  b.place(SwitchInput::StopLeft, -20300, -20000);  // a cam on the left input
  b.right_at(30000);
  b.place(SwitchInput::Home, -150, 150);           // in the way, and ignored
  b.start();
  b.run(30000, true);
  b.through(50000, 300);
  CHECK_EQ(b.get(196), 50150);
  CHECK_EQ(b.get(11), 1);
  CHECK_EQ(b.get(9), 0);
  CHECK_EQ(b.edge_moving(1000), 151);
  PpsSearch c(67);
  c.left_at(-20000);
  c.place(SwitchInput::StopRight, 30000, 30300);
  c.start();
  c.run(20000, true);
  c.through(50000, 300);
  CHECK_EQ(c.get(196), 50150);
  CHECK_EQ(c.get(10), 1);
  CHECK_EQ(c.edge_moving(-1000), -151);
}

// With a left stop switch at one position, "the middle of the left end switch" is that position:
// 196 is the distance between the end switches (docs/errata.md, "196 after mode 3").
TEST(rfs_mode3_tmc5160_distance_between_the_end_switches) {
  PpsSearch b(3);
  b.between_end_switches(30000);
}

TEST(tmc5160_rfs_modes_4_and_68_one_switch_from_both_sides) {
  for (int mode : {4, 68}) {
    const int d = mode == 4 ? -1 : 1;  // toward the switch
    PpsSearch b(mode);
    if (d < 0)
      b.place(SwitchInput::StopLeft, -20300, -20000);
    else
      b.place(SwitchInput::StopRight, 20000, 20300);
    b.start();
    b.through(20000, 300);
    CHECK_EQ(b.get(d < 0 ? 11 : 10), 1);
    CHECK_EQ(b.get(196), 0);  // only modes 2 and 3 measure it
    CHECK_EQ(b.edge_moving(-d * 1000), static_cast<std::int32_t>(-d * 151));
  }
}

TEST(tmc5160_rfs_modes_5_and_6_home_switch_turning_at_the_end_switch) {
  for (int mode : {5, 6}) mt::home_turning_at_the_end_switch<PpsSearch>(mode);  // 9: the home switch's own state
}

// The end switches in the way are passed with their stop functions on (7.1: they do not influence
// the search).
TEST(tmc5160_rfs_modes_7_8_and_136_home_switch_ignoring_end_switches) {
  for (int mode : {7, 8}) mt::home_ignoring_end_switches<PpsSearch>(mode);
  PpsSearch c(8 + 128);  // +128: the home switch reads inverted, "closed" outside its range
  c.place(SwitchInput::Home, -150, 150);
  c.start();
  c.run(151, true);
  c.run(1, false);
  c.run(1, false);
  c.move(1);
  c.done();
  CHECK_EQ(c.edge_moving(-1000), -1);
}

// The SixPoint settings shape the last move onto the reference point (a positioning), not the
// search's runs (velocity mode); with soft stops (26) it still ends on the reference point.
TEST(tmc5160_rfs_with_sixpoint_and_soft_stops_ends_on_the_reference_point) {
  for (int mode : {1, 3, 66, 7}) {
    PpsSearch b(mode);
    b.sixpoint(100, 20000, 2000, 51200, 51200, 30000, 10000, 200);
    b.set(26, 1);
    b.ends_on_the_reference_point();
    CHECK_EQ(b.edge_moving(mode == 66 ? -100 : mode == 7 ? -1000 : 100), mode == 66 ? -1 : mode == 7 ? -151 : 1);
  }
}

TEST(tmc5160_rfs_that_never_meets_its_switch_runs_until_stopped) {
  PpsSearch b(1);
  b.start();
  CHECK_EQ(b.core->next_event(), tmcl::kNever);
  b.to(10000000);
  CHECK(b.core->position(0) < -400000);
  CHECK_EQ(b.core->reference_search(0, tmcl::RfsAction::Status), 1);
  b.core->reference_search(0, tmcl::RfsAction::Stop);
  CHECK(b.core->reference_done(0));
  CHECK(b.until(MotionEventKind::Stopped));
  CHECK_EQ(b.count(MotionEventKind::ReferenceDone), 0);
}

// MVP REL counts from the last target (127 = 0) or from the actual position (127 = 1).
TEST(tmc5160_relative_moves_follow_parameter_127) {
  Drive b;
  b.right_at(30000);
  b.core->move_absolute(0, 50000);
  CHECK(b.until(MotionEventKind::Stopped));  // at the switch, 30000
  b.set(12, 1);
  b.core->move_relative(0, -1000);
  CHECK(b.until(MotionEventKind::TargetReached));
  CHECK_EQ(b.core->position(0), 49000);
  b.core->move_absolute(0, 0);
  CHECK(b.until(MotionEventKind::TargetReached));
  b.set(12, 0);
  b.core->move_absolute(0, 50000);
  CHECK(b.until(MotionEventKind::Stopped));
  b.set(127, 1);
  b.set(12, 1);
  b.core->move_relative(0, -1000);
  CHECK(b.until(MotionEventKind::TargetReached));
  CHECK_EQ(b.core->position(0), 29000);
}

// With a stop speed of thousands of pps the last nanosecond before an arrival is more than the
// step tolerance: an arrival just after a whole microsecond, reported at it, read one step short
// of the target (found by motion_bench; 5 of the first 3000 of these moves).
TEST(tmc5160_an_arrival_at_a_stop_speed_reads_its_target) {
  Drive b;
  b.sixpoint(1000, 100000, 20000, 50000, 60000, 40000, 80000, 2000);
  std::mt19937 rng(2024);
  std::uniform_int_distribution<std::int32_t> pick(-1000, 1000);
  int wrong = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::int32_t target = pick(rng);
    b.core->move_absolute(0, target);
    b.next();
    wrong += !b.core->target_reached(0) || b.core->position(0) != target;
  }
  CHECK_EQ(wrong, 0);
}

TEST(tmc5160_a_parameter_written_while_cruising_reports_no_second_velocity_reached) {
  Drive b;
  mt::cruise_reports_velocity_reached_once(b, 5, 30000, 20000);
}
