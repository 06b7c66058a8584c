// The other modules' load measurements (stall.hpp, stall_core.cpp; docs/motion.md, "Loads,
// stalls and lost steps"; errata E74-E76): the TMCM-351's stallGuard 1 (load value 0..7 rising
// with the load, stop at the threshold 205 at a constant speed only, 207 bit 1), the TMCM-1260's
// 207 bit 0 on a stop on stall, and the TMC2300-MOTOR-EVAL's StallGuard4 (reading not shifted by
// 174, stop when it falls to 2 · 174 at a speed >= 181, only in StealthChop).
#include <vector>

#include "check.hpp"
#include "helpers.hpp"
#include "stall.hpp"

using tmcl::MotionEventKind;
using tmcl::SwitchInput;

namespace {

// A TMCM-351 axis at 16 microsteps, pulse divisor 3, ramp divisor 7: 400 = 12207 pps.
struct Axis351 : mt::SwitchBench {
  Axis351() : SwitchBench("tmc429", "tmcm-351", 3) {
    set(140, 4);
    set(154, 3);
    set(153, 7);
    set(5, 1000);
  }
  void cruise() {
    core->rotate(0, 400);
    CHECK(until(MotionEventKind::VelocityReached));
  }
  void load(int percent) { CHECK(core->set_load(0, percent)); }
  void wait(tmcl::SimTime d) { to(now + d); }
};

int index_of(const std::vector<tmcl::MotionEvent>& ev, MotionEventKind kind) {
  for (std::size_t i = 0; i < ev.size(); ++i)
    if (ev[i].kind == kind) return static_cast<int>(i);
  return -1;
}

}  // namespace

// stallGuard 1: the load value rises with the load from 0 (free) to 7 (100 % and above).
TEST(sg1_load_value_rises_with_the_load) {
  Axis351 b;
  b.cruise();
  b.wait(20000);
  CHECK_EQ(b.get(206), 0);
  int last = 0;
  for (int p : {20, 40, 60, 80, 100, 300}) {
    b.load(p);
    b.wait(20000);
    const int v = b.get(206);
    CHECK(v >= last);
    CHECK_EQ(v, tmcl::stall::reading1(p));
    last = v;
  }
  CHECK_EQ(last, 7);
  CHECK_EQ(tmcl::stall::reading1(50), 4);
  CHECK_EQ(b.count(MotionEventKind::Stall), 0);  // 205 = 0: no stall detection
  CHECK_EQ(b.get(208), 0);                        // 208 holds driver faults only on this module
}

// The motor stops when the load value reaches the threshold 205; 207 bit 1 says why until the
// next motion command; 208 stays 0.
TEST(sg1_stops_at_the_threshold) {
  Axis351 b;
  b.set(205, 5);
  b.cruise();
  b.load(60);  // reads 4: below 5
  b.wait(100000);
  CHECK_EQ(b.get(206), 4);
  CHECK_EQ(b.count(MotionEventKind::Stall), 0);
  b.load(80);  // reads 6
  CHECK(b.until(MotionEventKind::Stall));
  CHECK_EQ(b.count(MotionEventKind::Stall), 1);
  CHECK_EQ(b.get(3), 0);
  CHECK(b.get(206) >= 5);
  CHECK_EQ(b.get(207), 2);
  CHECK_EQ(b.get(207), 2);  // not cleared by reading on this module
  CHECK_EQ(b.get(208), 0);
  CHECK(b.next() == tmcl::kNever);
  b.core->rotate(0, -400);  // "cleared with the next movement command"
  CHECK_EQ(b.get(207), 0);
}

// "There is no stall detection while the motor is being accelerated or decelerated": under a
// blocking load from rest the stall comes once the ramp reaches its speed, not before.
TEST(sg1_no_detection_while_accelerating) {
  Axis351 b;
  b.set(205, 1);
  b.load(100);
  b.core->rotate(0, 400);
  CHECK(b.until(MotionEventKind::Stall));
  const int reached = index_of(b.events, MotionEventKind::VelocityReached);
  const int stall = index_of(b.events, MotionEventKind::Stall);
  CHECK(reached >= 0 && reached < stall);
  CHECK(b.events[static_cast<std::size_t>(stall)].at >= b.events[static_cast<std::size_t>(reached)].at);
  CHECK_EQ(b.get(207), 2);
  // The steps the counter made while the held shaft waited for the ramp's end were lost: said once.
  CHECK_EQ(b.count(MotionEventKind::StepsLost), 1);
  CHECK(index_of(b.events, MotionEventKind::StepsLost) < reached);
}

// A TMCM-351 homing into a hard stop with stall detection: it stops within a fullstep past it.
TEST(sg1_hard_stop_homing) {
  Axis351 b;
  b.set(205, 5);
  CHECK(b.core->place_hard_stop(0, SwitchInput::StopLeft, -20000));
  b.core->rotate(0, -400);
  CHECK(b.until(MotionEventKind::Stall, 40));
  const std::int32_t p = b.core->position(0);
  CHECK(p <= -20000 && p >= -20000 - 16 - 1);
  CHECK_EQ(b.get(206), 7);
}

// PD60-1260 (TMCM-1260): a stop on stall sets 207 bit 0 ("1 StallGuard error"), which reading
// clears there, as a motion command does.
TEST(tmcm1260_stall_sets_207_bit_0) {
  mt::SwitchBench b("tmc5160", "tmcm-1260", 1);
  b.set(140, 8);
  b.set(6, 128);
  b.set(5, 1000000);
  b.set(181, 40000);
  b.core->rotate(0, 51200);
  CHECK(b.until(MotionEventKind::VelocityReached));
  CHECK_EQ(b.get(207), 0);
  CHECK(b.core->set_load(0, 100));
  CHECK(b.until(MotionEventKind::Stall));
  CHECK_EQ(b.get(208) & 1, 1);
  CHECK_EQ(b.get(207), 1);
  CHECK_EQ(b.get(207), 0);  // "cleared automatically when this parameter has been read out"
  b.core->rotate(0, 51200);
  CHECK(b.until(MotionEventKind::Stall));
  b.core->rotate(0, -51200);
  CHECK_EQ(b.get(207), 0);  // ... "or when a motion command has been executed"
}

// Every bundled stallGuard2 module on the TMC429 core whose profile says what a stop on stall sets
// in 207 (TMCM-1110, -1140, -1160, -1161, -3110, -6110: "1: stallGuard error", errata E76): the stall sets
// it beside 208 bit 0, and the next motion command clears it (reading does not: only the
// PD57/60-1260's manual says so).
TEST(tmc429_modules_stall_sets_their_207_flag) {
  int modules = 0;
  for (const tmcl::Profile* p : tmcl::all_profiles()) {
    const std::int64_t flag = p->motion_constant("stall-flag", 0);
    if (p->default_motion != "tmc429" || flag == 0 || !p->axis_param(174)) continue;  // stallGuard2
    ++modules;
    const std::string name(p->name);
    mt::SwitchBench b("tmc429", name.c_str(), 1);
    b.set(140, 4);  // 16 microsteps
    b.set(154, 3);
    b.set(153, 7);
    b.set(5, 1000);
    b.set(181, 100);
    CHECK(b.core->place_hard_stop(0, tmcl::SwitchInput::StopLeft, -5000));
    b.core->rotate(0, -400);  // 763 fullsteps/s into the hard stop
    CHECK(b.until(MotionEventKind::VelocityReached));
    CHECK_EQ(b.get(207), 0);
    CHECK(b.until(MotionEventKind::Stall, 20));
    CHECK_EQ(b.get(208) & 1, 1);
    CHECK_EQ(b.get(207), flag);
    CHECK_EQ(b.get(207), flag);  // still set after reading
    b.core->rotate(0, 400);
    CHECK_EQ(b.get(207), 0);  // cleared by the next motion command
  }
  CHECK_EQ(modules, 6);
}

namespace {

// A TMC2300-MOTOR-EVAL (linear core) at 16 microsteps rotating at 16000 pps = 1000 fullsteps/s,
// run current 16.
struct Axis2300 : mt::SwitchBench {
  explicit Axis2300(bool run = true) : SwitchBench("linear", "tmc2300-eval", 1) {
    set(140, 4);
    set(6, 16);
    set(5, 200000);
    if (run) cruise(16000);
  }
  void cruise(std::int32_t v) {
    core->rotate(0, v);
    CHECK(until(MotionEventKind::VelocityReached));
  }
  void load(int percent) { CHECK(core->set_load(0, percent)); }
  void wait(tmcl::SimTime d) { to(now + d); }
};

}  // namespace

// StallGuard4: the reading falls linearly with the load from the no-load value; the threshold 174
// does not shift it (it is only the level a stall is compared with).
TEST(sg4_load_value_falls_with_the_load_not_shifted_by_174) {
  Axis2300 b;
  b.wait(20000);
  CHECK_EQ(b.get(206), tmcl::stall::reading4(1000, 16, 0));
  CHECK_EQ(b.get(206), 427);  // 250 + 500 · 17/32 · 1000/1500, rounded
  int last = 1024;
  for (int p : {10, 40, 70, 99}) {
    b.load(p);
    b.wait(20000);
    const int v = b.get(206);
    CHECK(v < last);
    CHECK_EQ(v, tmcl::stall::reading4(1000, 16, p));
    last = v;
  }
  b.load(50);
  b.wait(20000);
  const int at50 = b.get(206);
  b.set(174, 60);
  b.wait(20000);
  CHECK_EQ(b.get(206), at50);  // unlike stallGuard2's 174
  CHECK_EQ(b.get(180), 16);    // the run current while moving (no coolStep)
}

// Stop on stall: the first measurement at or below 2 · 174 at a speed >= 181 stops the motor at
// once; the stall event carries that reading. A higher 174 stops under a smaller load.
TEST(sg4_stops_at_twice_174_above_181) {
  {
    Axis2300 b;
    b.set(181, 10000);
    b.set(174, 100);  // stall at a reading <= 200
    b.load(40);       // reads 256
    b.wait(100000);
    CHECK_EQ(b.count(MotionEventKind::Stall), 0);
    b.load(60);  // reads 171
    CHECK(b.until(MotionEventKind::Stall));
    CHECK_EQ(b.get(3), 0);
    CHECK_EQ(b.get(206), tmcl::stall::reading4(1000, 16, 60));
    CHECK_EQ(b.last().value, b.get(206));
    CHECK(b.next() == tmcl::kNever);
  }
  {
    Axis2300 b;
    b.set(181, 10000);
    b.set(174, 150);  // more sensitive: <= 300 stops
    b.load(40);
    CHECK(b.until(MotionEventKind::Stall));
  }
  {
    Axis2300 b;
    b.set(181, 20000);  // above the speed: no stop, the blocked rotor loses steps
    b.load(100);
    CHECK(b.until(MotionEventKind::StepsLost));
    b.wait(500000);
    CHECK_EQ(b.count(MotionEventKind::Stall), 0);
    CHECK_EQ(b.get(3), 16000);
    CHECK_EQ(b.get(206), 0);
  }
}

// "StallGuard4 in StealthChop mode": with 187 = 0 (StealthChop off) nothing is measured, 206
// holds and no stall stops the motor.
TEST(sg4_needs_stealthchop) {
  Axis2300 b;
  b.wait(20000);
  const int free = b.get(206);
  b.set(187, 0);
  b.set(181, 1000);
  b.load(100);
  b.wait(500000);
  CHECK_EQ(b.get(206), free);
  CHECK_EQ(b.count(MotionEventKind::Stall), 0);
  b.set(187, 1);  // on again: the next measurement stalls
  CHECK(b.until(MotionEventKind::Stall));
}

// Homing into a hard stop on the TMC2300 with stop on stall: within a fullstep past the stop.
TEST(sg4_hard_stop_homing) {
  Axis2300 b(false);
  b.set(181, 1000);
  CHECK(b.core->place_hard_stop(0, SwitchInput::StopLeft, -8000));
  b.core->rotate(0, -16000);
  CHECK(b.until(MotionEventKind::Stall, 40));
  const std::int32_t p = b.core->position(0);
  CHECK(p <= -8000 && p >= -8000 - 16 - 1);
  CHECK_EQ(b.get(206), 0);
  CHECK_EQ(b.get(180), 8);  // at rest: the standby current
}

// coolStep on the TMC2300 (errata E73): the same rules as on the TMCM modules (coolstep.hpp), on
// StallGuard4's readings, and only while StealthChop measures (187 > 0). Lower threshold 172 = 2
// (64), upper (2 + 3 + 1) · 32 = 192, a down-step per reading above it (169 = 3), up-steps of 2
// (171 = 1), least scale half the run current 16: 7. A reading every millisecond at 16000 pps.
namespace {
struct Cool2300 : Axis2300 {
  Cool2300() : Axis2300(false) {
    set(172, 2);
    set(170, 3);
    set(169, 3);
    set(171, 1);
  }
};
}  // namespace

TEST(coolstep_on_the_tmc2300_follows_the_rules_on_stallguard4) {
  Cool2300 b;
  CHECK_EQ(b.get(180), 8);  // at rest: the standby current
  b.cruise(16000);
  b.wait(50000);
  // Free: 427 at scale 16 is above 192, down to 7, where StallGuard4 reads 250 + 500 · 8/32 · 2/3.
  CHECK_EQ(b.get(180), 7);
  CHECK_EQ(b.get(206), tmcl::stall::reading4(1000, 7, 0));
  CHECK_EQ(b.get(206), 333);
  // 85 %: 333 · 0.15 = 50 is below 64, up by 2 per reading until the reading is in the band (at
  // the run current 16, 427 · 0.15 = 64).
  b.load(85);
  b.wait(50000);
  CHECK_EQ(b.get(180), 16);
  CHECK_EQ(b.get(206), tmcl::stall::reading4(1000, 16, 85));
  // The steps were events: 16 down to 7 one by one, then up 7, 9, ..., 15, 16.
  std::vector<int> steps;
  for (const auto& e : b.events)
    if (e.kind == MotionEventKind::CurrentChanged) steps.push_back(e.value);
  CHECK((steps == std::vector<int>{15, 14, 13, 12, 11, 10, 9, 8, 7, 9, 11, 13, 15, 16}));
  b.load(0);
  b.wait(50000);
  CHECK_EQ(b.get(180), 7);
  b.core->stop(0);
  b.wait(200000);
  CHECK_EQ(b.get(180), 8);  // at rest: the standby current
}

// No coolStep without StallGuard4's readings (187 = 0: StealthChop off) nor below 182: 180 stays
// the run current and no step is an event. 187 = 0 while regulating brings it back to 6.
TEST(coolstep_on_the_tmc2300_needs_stealthchop_and_182) {
  {
    Cool2300 b;
    b.set(187, 0);
    b.cruise(16000);
    b.wait(50000);
    CHECK_EQ(b.get(180), 16);
    CHECK_EQ(b.count(MotionEventKind::CurrentChanged), 0);
    b.set(187, 1);  // StealthChop again: regulation starts
    b.wait(50000);
    CHECK_EQ(b.get(180), 7);
    const int before = b.count(MotionEventKind::CurrentChanged);
    b.set(187, 0);  // off while at 7: back to the run current at the next fullstep, in one step
    b.wait(5000);
    CHECK_EQ(b.get(180), 16);
    CHECK_EQ(b.count(MotionEventKind::CurrentChanged), before + 1);
    CHECK_EQ(b.last().value, 16);
  }
  {
    Cool2300 b;
    b.set(182, 16001);  // pps: just above the speed
    b.cruise(16000);
    b.wait(50000);
    CHECK_EQ(b.get(180), 16);
    CHECK_EQ(b.count(MotionEventKind::CurrentChanged), 0);
    b.set(182, 16000);  // at the speed: it regulates
    b.wait(50000);
    CHECK_EQ(b.get(180), 7);
  }
}
