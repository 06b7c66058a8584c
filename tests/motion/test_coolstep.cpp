// coolStep (coolstep.hpp, coolstep_core.cpp; docs/motion.md, "coolStep"): the current steps
// against the manuals' rules (TMCM-1110 manual 5 and 5.2, PD57/60-1260 manual 4 and 7.3): up-steps
// of 1, 2, 4, 8 (171) for each reading below the lower threshold 172 · 32, one down-step after 32,
// 8, 2 or 1 readings (169) at or above the upper one (172 + 170 + 1) · 32, never below 1/2 or 1/4 of
// the run current (168) nor above it, only at or above the threshold speed 182; the actual current
// 180 readable, each change an event; the load value read with the current driven.
#include <vector>

#include "check.hpp"
#include "coolstep.hpp"
#include "helpers.hpp"
#include "stall.hpp"

using tmcl::MotionEventKind;
namespace cs = tmcl::coolstep;

namespace {

// A TMCM-1260 (pps) at 51200 pps = 200 fullsteps/s with 256 microsteps, run current 128 (scale 16),
// standby 8 (scale 1); a measurement every fullstep, 5 ms.
struct Cool1260 : mt::SwitchBench {
  Cool1260() : SwitchBench("tmc5160", "tmcm-1260", 1) {
    set(140, 8);
    set(6, 128);
    set(7, 8);
    set(5, 1000000);
    core->rotate(0, 51200);
    CHECK(until(MotionEventKind::VelocityReached));
  }
  void wait(tmcl::SimTime d) { to(now + d); }
  // The values of the CurrentChanged events so far, and their instants.
  std::vector<int> steps() const {
    std::vector<int> v;
    for (const auto& e : events)
      if (e.kind == MotionEventKind::CurrentChanged) v.push_back(e.value);
    return v;
  }
  std::vector<tmcl::SimTime> instants() const {
    std::vector<tmcl::SimTime> v;
    for (const auto& e : events)
      if (e.kind == MotionEventKind::CurrentChanged) v.push_back(e.at);
    return v;
  }
  // Runs event by event for `d` microseconds (every step is an event).
  void run(tmcl::SimTime d) {
    const tmcl::SimTime end = now + d;
    for (tmcl::SimTime t = core->next_event(); t <= end; t = core->next_event()) to(t);
    to(end);
  }
};

}  // namespace

// The rules alone, as the manuals' tables give them.
TEST(coolstep_rules_follow_the_manual) {
  cs::Settings s{31, 0, 3, 2, 0, 1};  // run scale 31, 1/2, a down-step per reading, 170 = 2, +1, 172 = 1
  CHECK_EQ(cs::lower(s), 32);
  CHECK_EQ(cs::upper(s), 128);  // (1 + 2 + 1) · 32
  CHECK(cs::enabled(s));
  CHECK(!cs::enabled(cs::Settings{31, 0, 0, 0, 0, 0}));  // 172 = 0: off
  CHECK_EQ(cs::minimum(s), 15);                          // 16/32: half of 32/32
  s.seimin = 1;
  CHECK_EQ(cs::minimum(s), 7);  // 8/32: a quarter
  s.seimin = 0;
  for (int seup : {0, 1, 2, 3}) {
    s.seup = seup;
    CHECK_EQ(cs::up_step(s), (std::vector<int>{1, 2, 4, 8}[static_cast<std::size_t>(seup)]));
  }
  for (int sedn : {0, 1, 2, 3}) {
    s.sedn = sedn;
    CHECK_EQ(cs::down_after(s), (std::vector<int>{32, 8, 2, 1}[static_cast<std::size_t>(sedn)]));
  }
  // Below the lower threshold: up by the step, not above the run current.
  s.seup = 2;
  CHECK_EQ(cs::measure({20, 0}, s, 31).cs, 24);
  CHECK_EQ(cs::measure({29, 0}, s, 0).cs, 31);
  // In the band: nothing, and the count of readings above starts again.
  CHECK_EQ(cs::measure({20, 5}, s, 32), (cs::State{20, 0}));
  CHECK_EQ(cs::measure({20, 5}, s, 127), (cs::State{20, 0}));
  // At or above the upper threshold: one down-step per 8 readings (169 = 1).
  s.sedn = 1;
  cs::State st{20, 0};
  for (int i = 0; i < 7; ++i) st = cs::measure(st, s, 128);
  CHECK_EQ(st, (cs::State{20, 7}));
  st = cs::measure(st, s, 1000);
  CHECK_EQ(st, (cs::State{19, 0}));
  // Never below the minimum.
  s.sedn = 3;
  st = {16, 0};
  for (int i = 0; i < 10; ++i) st = cs::measure(st, s, 500);
  CHECK_EQ(st.cs, 15);
}

// Off (172 = 0, the default): 180 is the run current's scale while moving, the standby current's
// at rest, and nothing steps.
TEST(coolstep_off_reads_run_and_standby_current) {
  Cool1260 b;
  CHECK_EQ(b.get(180), 16);
  b.wait(1000000);
  CHECK_EQ(b.get(180), 16);
  CHECK(b.steps().empty());
  b.core->stop(0);
  CHECK(b.until(MotionEventKind::Stopped));
  CHECK_EQ(b.get(180), 1);  // 8 of 0..255 in 32 steps
}

// No load reads 326 at scale 16, above the upper threshold 128: one down-step per reading (169 = 3)
// down to half the run current (7: 8/32 of 17/32), one event each, a fullstep (5 ms) apart; the load
// value is then read with the lower current.
TEST(coolstep_steps_down_above_the_upper_threshold_to_the_minimum) {
  Cool1260 b;
  b.set(170, 2);
  b.set(169, 3);
  b.set(172, 1);  // on: lower 32, upper 128
  b.run(200000);
  CHECK_EQ(b.steps(), (std::vector<int>{15, 14, 13, 12, 11, 10, 9, 8, 7}));
  const auto at = b.instants();
  for (std::size_t i = 1; i < at.size(); ++i) CHECK(at[i] - at[i - 1] >= 4999 && at[i] - at[i - 1] <= 5001);
  CHECK_EQ(b.get(180), 7);
  CHECK_EQ(b.get(206), tmcl::stall::reading(200, 7, 0, 0));  // 286: measured with the current driven
  // 168 = 1: down to a quarter (3: 4/32 of 17/32).
  b.set(168, 1);
  b.run(200000);
  CHECK_EQ(b.get(180), 3);
  // At rest: the standby current; moving again, the regulation starts from the run current.
  b.core->stop(0);
  CHECK(b.until(MotionEventKind::Stopped));
  CHECK_EQ(b.get(180), 1);
}

// 169 = 0: a down-step after 32 readings above the upper threshold, 160 ms apart.
TEST(coolstep_down_step_counts_readings) {
  Cool1260 b;
  b.set(170, 2);
  b.set(172, 1);
  b.run(400000);
  CHECK_EQ(b.steps(), (std::vector<int>{15, 14}));
  const auto at = b.instants();
  CHECK(at[1] - at[0] >= 159999 && at[1] - at[0] <= 160001);
}

// A load that pushes the reading below the lower threshold: up-steps of 171's size, capped at the
// run current; the load gone, down again.
TEST(coolstep_steps_up_below_the_lower_threshold) {
  Cool1260 b;
  b.set(170, 2);
  b.set(169, 3);
  b.set(171, 2);  // up-steps of 4
  b.set(172, 1);
  b.run(200000);
  CHECK_EQ(b.get(180), 7);
  const std::size_t before = b.steps().size();
  CHECK(b.core->set_load(0, 95));  // 286 · 0.05 = 14 < 32
  b.run(100000);
  const auto s = b.steps();
  CHECK_EQ(std::vector<int>(s.begin() + static_cast<long>(before), s.end()), (std::vector<int>{11, 15, 16}));
  CHECK_EQ(b.get(180), 16);
  CHECK(b.core->set_load(0, 0));
  b.run(200000);
  CHECK_EQ(b.get(180), 7);
}

// The threshold speed 182: below it coolStep does not regulate (180 is the run current), at or
// above it does; slowing below it brings the run current back at the next reading.
TEST(coolstep_only_at_or_above_the_threshold_speed) {
  {
    Cool1260 b;
    b.set(170, 2);
    b.set(169, 3);
    b.set(182, 51201);  // just above the speed
    b.set(172, 1);
    b.run(500000);
    CHECK(b.steps().empty());
    CHECK_EQ(b.get(180), 16);
  }
  Cool1260 b;
  b.set(170, 2);
  b.set(169, 3);
  b.set(182, 51200);  // the speed itself: on
  b.set(172, 1);
  b.run(200000);
  CHECK_EQ(b.get(180), 7);
  b.core->rotate(0, 40000);  // slower than 182: back to the run current
  b.run(200000);
  CHECK_EQ(b.steps().back(), 16);
  CHECK_EQ(b.get(180), 16);
}

// The TMCM-1110 (TMC429 units): 182 in velocity units, the current 0..255 in 32 steps.
TEST(coolstep_on_the_tmc429_core) {
  mt::SwitchBench b("tmc429", "tmcm-1110", 1);
  b.set(140, 4);  // 16 microsteps
  b.set(154, 3);
  b.set(153, 7);
  b.set(5, 1000);
  b.set(6, 255);  // scale 31
  b.set(170, 0);
  b.set(169, 3);
  b.set(172, 1);    // lower 32, upper 64
  b.set(182, 401);  // above 400 units: off
  b.core->rotate(0, 400);
  CHECK(b.until(MotionEventKind::VelocityReached));
  b.to(b.now + 500000);
  CHECK_EQ(b.get(180), 31);
  CHECK_EQ(b.count(MotionEventKind::CurrentChanged), 0);
  b.set(182, 400);
  b.to(b.now + 500000);
  CHECK_EQ(b.get(180), 15);  // half of 32/32
  CHECK_EQ(b.count(MotionEventKind::CurrentChanged), 16);
}

// With the filter (173 = 1) a reading comes every fourth fullstep: the steps are 20 ms apart.
TEST(coolstep_steps_at_the_filtered_readings) {
  Cool1260 b;
  b.set(173, 1);
  b.set(170, 2);
  b.set(169, 3);
  b.set(172, 1);
  b.run(300000);
  CHECK_EQ(b.steps(), (std::vector<int>{15, 14, 13, 12, 11, 10, 9, 8, 7}));
  const auto at = b.instants();
  for (std::size_t i = 1; i < at.size(); ++i) CHECK(at[i] - at[i - 1] >= 19999 && at[i] - at[i - 1] <= 20001);
}

// The load value is read with the current driven (errata E72): a sudden load of 97 % with 174 = -1
// reads 2 at the run current but 0 at a quarter of it, so stop on stall stops the motor only
// when coolStep has lowered the current.
TEST(coolstep_lowered_current_stalls_sooner) {
  for (bool cool : {false, true}) {
    Cool1260 b;
    b.set(174, -1);
    b.set(181, 40000);
    if (cool) {
      b.set(168, 1);
      b.set(170, 2);
      b.set(169, 3);
      b.set(172, 1);
    }
    b.run(300000);
    CHECK_EQ(b.get(180), cool ? 3 : 16);
    CHECK(b.core->set_load(0, 97));
    b.run(100000);
    CHECK_EQ(b.count(MotionEventKind::Stall), cool ? 1 : 0);
    CHECK_EQ(b.get(206), cool ? 0 : tmcl::stall::reading(200, 16, 97, -1));
  }
}
