// Shared helpers of the motion tests: a core on a profile, running to its next event, switches
// placed at positions, the closed-form move times, and the step-by-step expectations of a
// reference search.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "check.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"

namespace mt {

struct Bench {
  std::unique_ptr<tmcl::MotionCore> core;
  tmcl::SimTime now = 0;
  std::vector<tmcl::MotionEvent> events;

  explicit Bench(const char* core_name = "tmc4361", const char* profile = "usb-2-sd", int motors = 1)
      : core(tmcl::make_motion_core(core_name)) {
    core->reset(*tmcl::find_profile(profile), motors);
  }
  void set(int param, std::int32_t v, int motor = 0) { CHECK(core->set_param(motor, param, v) == tmcl::ParamWrite::Ok); }
  std::int32_t get(int param, int motor = 0) { return core->get_param(motor, param); }
  void to(tmcl::SimTime t) {
    now = t;
    core->advance(t, events);
  }
  // Advances to the next event; returns its instant (kNever: none).
  tmcl::SimTime next() {
    tmcl::SimTime t = core->next_event();
    if (t != tmcl::kNever) to(t);
    return t;
  }
  const tmcl::MotionEvent& last() const { return events.back(); }
};

inline bool near(double a, double b, double rel = 1e-9, double abs = 1e-9) {
  return std::fabs(a - b) <= abs + rel * std::max(std::fabs(a), std::fabs(b));
}

// A duration in seconds as simulated microseconds, rounded up (a tick that is 1e-3 µs over the
// whole number is float noise, not another microsecond).
inline tmcl::SimTime us(double seconds) { return static_cast<tmcl::SimTime>(std::ceil(seconds * 1e6 - 1e-3)); }

// A Bench with switches at positions, run event by event.
struct SwitchBench : Bench {
  using Bench::Bench;
  void left_at(std::int64_t p) { CHECK(core->place_switch(0, tmcl::SwitchInput::StopLeft, INT64_MIN, p)); }
  void right_at(std::int64_t p) { CHECK(core->place_switch(0, tmcl::SwitchInput::StopRight, p, INT64_MAX)); }
  void place(tmcl::SwitchInput in, std::int64_t lo, std::int64_t hi) { CHECK(core->place_switch(0, in, lo, hi)); }
  // Runs until an event of `kind` (or nothing more can happen); true when it came.
  bool until(tmcl::MotionEventKind kind, int limit = 100) {
    for (int i = 0; i < limit; ++i) {
      std::size_t n = events.size();
      if (next() == tmcl::kNever) return false;
      for (std::size_t k = n; k < events.size(); ++k)
        if (events[k].kind == kind) return true;
    }
    return false;
  }
  int count(tmcl::MotionEventKind kind) const {
    int n = 0;
    for (const auto& e : events) n += e.kind == kind;
    return n;
  }
};

// A TMCM-1260 (pps) at 256 microsteps and current scale 16 (6 = 128), A2 = 1000000 pps²; with
// `cruising` rotating at 51200 pps = 200 fullsteps/s (the stall and StealthChop tests).
struct Axis1260 : SwitchBench {
  explicit Axis1260(bool cruising = true) : SwitchBench("tmc5160", "tmcm-1260", 1) {
    set(140, 8);
    set(6, 128);
    set(5, 1000000);
    if (cruising) cruise();
  }
  void cruise() {
    core->rotate(0, 51200);
    CHECK(until(tmcl::MotionEventKind::VelocityReached));
  }
  void load(int percent) { CHECK(core->set_load(0, percent)); }
  void wait(tmcl::SimTime d) { to(now + d); }
};

// From rest, accelerating with a up to v: the time to cover `dist` steps.
inline double run_time(double dist, double v, double a) {
  if (dist <= v * v / (2 * a)) return std::sqrt(2 * dist / a);
  return v / a + (dist - v * v / (2 * a)) / v;
}
// A rest-to-rest move (trapezoid or triangle) with the same acceleration both ways.
inline double move_time(double dist, double v, double a) {
  return dist >= v * v / a ? dist / v + v / a : 2 * std::sqrt(dist / a);
}

// A reference search checked step by step, on a SwitchBench B with hard stops: search speed vs,
// switch speed vc, acceleration a both ways (pps, pps²).
template <class B>
struct Searching : B {
  double vs, vc, a;
  tmcl::SimTime t = 0;
  Searching(double search, double calibrate, double accel) : vs(search), vc(calibrate), a(accel) {}
  // The expected instants, step by step: each step starts from rest at the microsecond the last
  // one was reported.
  void run(double dist, bool fast) { t += us(run_time(dist, fast ? vs : vc, a)); }
  void move(double dist) { t += us(move_time(dist, vc, a)); }
  // A switch with one edge met after `dist` at the search speed: one step out of it and one in
  // again at the switch speed, and the search is done there.
  void one_edge(double dist) {
    run(dist, true);
    run(1, false);
    run(1, false);
    done();
  }
  // Modes 2 and 3 (+64: the other way round) between a left stop switch at -20000 and a right
  // one at 30000, from 0: `first` steps to the end switch searched first, 50000 to the other,
  // whose edge is the reference point; 196 is the distance between them.
  void between_end_switches(double first) {
    this->left_at(-20000);
    this->right_at(30000);
    start();
    run(first, true);
    one_edge(50000);
    CHECK_EQ(this->get(196), 50000);
  }
  // Between end switches at -20000 and 30000, a home range [1000, 1300]: the search (whatever
  // its stops and ramps) ends at rest on its reference point, which is position 0 and the target.
  void ends_on_the_reference_point() {
    this->left_at(-20000);
    this->right_at(30000);
    this->place(tmcl::SwitchInput::Home, 1000, 1300);
    start();
    CHECK(this->until(tmcl::MotionEventKind::ReferenceDone));
    CHECK_EQ(this->core->position(0), 0);
    CHECK(this->core->target_reached(0));
  }
  // A range [lo, lo + width] (a cam, a home switch) met after `dist`: one step out, back in and
  // through it, then to its centre.
  void through(double dist, double width) {
    run(dist, true);
    run(1, false);
    run(width + 2, false);
    move(width / 2 + 1);
    done();
  }
  void start() {
    this->to(this->now);  // the switches' state at power-on, as the VM collects it before a program runs
    CHECK_EQ(this->core->reference_search(0, tmcl::RfsAction::Start), 0);
    CHECK(!this->core->reference_done(0));
    CHECK_EQ(this->core->reference_search(0, tmcl::RfsAction::Status), 1);
  }
  void done() {
    CHECK(this->until(tmcl::MotionEventKind::ReferenceDone));
    CHECK(this->core->reference_done(0));
    CHECK_EQ(this->core->reference_search(0, tmcl::RfsAction::Status), 0);
    CHECK_EQ(this->core->position(0), 0);
    CHECK_EQ(this->get(0), 0);
    CHECK_EQ(this->get(3), 0);
    CHECK(this->core->target_reached(0));
    const tmcl::SimTime at = this->now;
    if (std::llabs(at - t) > 3) std::fprintf(stderr, "done at %lld us, expected %lld\n", (long long)at, (long long)t);
    CHECK(std::llabs(at - t) <= 3);
  }
  // Where the reference point is: the first switch change of a move from it.
  std::int32_t edge_moving(std::int32_t target) {
    this->core->move_absolute(0, target);
    CHECK(this->until(tmcl::MotionEventKind::SwitchChanged));
    return this->last().position;
  }
};

// Modes 5 (toward -) and 6 (toward +) on a Searching S: the end switch at -+20000 on the way
// turns the search around, the home range of 300 steps on the other side is crossed, and its
// centre is the reference point; 9 reads the home switch, 10 and 11 open.
template <class S>
void home_turning_at_the_end_switch(int mode) {
  const int d = mode == 5 ? -1 : 1;
  S b(mode);
  b.left_at(-20000);
  b.right_at(20000);
  b.place(tmcl::SwitchInput::Home, d < 0 ? 5000 : -5300, d < 0 ? 5300 : -5000);
  b.start();
  b.run(20000, true);  // the end switch turns the search around
  b.through(25000, 300);
  CHECK_EQ(b.get(9), 1);
  CHECK_EQ(b.get(10), 0);
  CHECK_EQ(b.get(11), 0);
  CHECK_EQ(b.edge_moving(-d * 1000), static_cast<std::int32_t>(-d * 151));
}

// Modes 7 (toward +) and 8 (toward -): the end switch at +-500 in the way is passed (no stop
// function stops a search), the home range of 200 steps beyond it is crossed.
template <class S>
void home_ignoring_end_switches(int mode) {
  const int d = mode == 7 ? 1 : -1;
  S b(mode);
  b.left_at(-500);
  b.right_at(500);
  b.place(tmcl::SwitchInput::Home, d > 0 ? 1000 : -1200, d > 0 ? 1200 : -1000);
  b.start();
  b.through(1000, 200);
  CHECK_EQ(b.get(9), 1);
  CHECK_EQ(b.get(d > 0 ? 10 : 11), 1);  // it stands beyond the end switch
}

// docs/motion.md, decision 17: a parameter written while the motor cruises at its target speed
// (here its acceleration, `accel_param`) re-plans it without a second "velocity reached"; a
// command (ROR again) reports it again.
template <class S>
void cruise_reports_velocity_reached_once(S& b, int accel_param, std::int32_t v, std::int32_t accel) {
  using tmcl::MotionEventKind;
  b.core->rotate(0, v);
  CHECK(b.until(MotionEventKind::VelocityReached));
  b.to(b.now + 100000);
  b.set(accel_param, accel);
  b.to(b.now + 100000);
  CHECK_EQ(b.count(MotionEventKind::VelocityReached), 1);
  b.core->rotate(0, v);
  b.to(b.now + 1);
  CHECK_EQ(b.count(MotionEventKind::VelocityReached), 2);
}

}  // namespace mt
