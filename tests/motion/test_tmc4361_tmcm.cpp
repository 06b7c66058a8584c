// The `tmc4361` core under the TMCM modules with a TMC4361A-style controller per axis (TMCM-3351,
// TMCM-3312: docs/profiles.md): three axes, each with its own S-shaped or SixPoint ramp from the
// module's own parameter numbers, taking the closed-form times of design/ramps.md's reference
// cases; and the switch states 9, 10 and 11, which the USB-2-SD has not.
#include "check.hpp"
#include "helpers.hpp"

namespace {

using mt::Bench;
using mt::us;
using tmcl::MotionEventKind;

// The instant each motor reports `target reached`, running the core to rest.
std::vector<tmcl::SimTime> arrivals(Bench& b, int motors) {
  std::vector<tmcl::SimTime> at(static_cast<std::size_t>(motors), tmcl::kNever);
  while (b.next() != tmcl::kNever)
    for (const auto& e : b.events)
      if (e.kind == MotionEventKind::TargetReached && at[e.motor] == tmcl::kNever) at[e.motor] = e.at;
  return at;
}

}  // namespace

TEST(tmcm3351_three_axes_take_their_own_ramps_in_closed_form) {
  for (const char* module : {"tmcm-3351", "tmcm-3312"}) {
    Bench b("tmc4361", module, 3);
    // Motor 0: S1 (S-shaped, D = 100000, V = A = 51200, bows 512000): 3.053125 s.
    // Motor 1: S3 (the same limits, D = 1000): 4 (D / 2J)^(1/3) = 0.396850263 s.
    // Motor 2: T1 (trapezoid, D = 100000, V = A = 51200): 2.953125 s.
    for (int m = 0; m < 2; ++m) b.set(14, 1, m);
    CHECK_EQ(b.get(22, 2), 512000);  // the bows' default (the USB-2-SD's row)
    b.core->move_absolute(0, 100000);
    b.core->move_absolute(1, -1000);
    b.core->move_absolute(2, 100000);
    const auto at = arrivals(b, 3);
    CHECK_EQ(at[0], us(3.053125));
    CHECK_EQ(at[1], us(4 * std::cbrt(1000.0 / (2 * 512000))));
    CHECK_EQ(at[2], us(2.953125));
    CHECK_EQ(b.core->position(0), 100000);
    CHECK_EQ(b.core->position(1), -1000);
    CHECK_EQ(b.core->position(2), 100000);
  }
}

TEST(tmcm3351_bows_and_scaling_are_per_axis) {
  Bench b("tmc4361", "tmcm-3351", 3);
  for (int m = 0; m < 3; ++m) b.set(14, 1, m);
  b.set(35, 2, 1);           // motor 1: bows x 2
  b.set(22, 1024000, 2);     // motor 2: every bow 1024000
  b.set(23, 1024000, 2);
  b.set(24, 1024000, 2);
  b.set(25, 1024000, 2);
  for (int m = 0; m < 3; ++m) b.core->move_absolute(m, 100000);
  const auto at = arrivals(b, 3);
  // Symmetric S-ramp, V = A = 51200, J: t_a = V/A + A/J, T = 2 t_a + (D - V t_a) / V.
  auto t = [](double j) {
    const double ta = 1.0 + 51200.0 / j;
    return 2 * ta + (100000.0 - 51200.0 * ta) / 51200.0;
  };
  CHECK_EQ(at[0], us(t(512000)));
  CHECK_EQ(at[1], us(t(1024000)));
  CHECK_EQ(at[2], us(t(1024000)));
}

TEST(tmcm3351_switch_states_read_timed_and_placed_switches) {
  Bench b("tmc4361", "tmcm-3351", 3);
  for (int p : {9, 10, 11}) CHECK_EQ(b.get(p, 1), 0);
  b.core->set_switch(1, tmcl::SwitchInput::StopRight, true);
  b.core->set_switch(1, tmcl::SwitchInput::Home, true);
  CHECK_EQ(b.get(10, 1), 1);
  CHECK_EQ(b.get(9, 1), 1);
  CHECK_EQ(b.get(11, 1), 0);
  CHECK_EQ(b.get(10, 0), 0);  // motor 0's own switch is open
  CHECK(b.core->set_param(1, 10, 0) == tmcl::ParamWrite::ReadOnly);
  b.core->set_switch(1, tmcl::SwitchInput::StopRight, false);
  CHECK_EQ(b.get(10, 1), 0);
  // A left switch placed at -5000 .. -4000 on motor 2: a move left stops where it closes, and
  // 11 reads it closed there.
  CHECK(b.core->place_switch(2, tmcl::SwitchInput::StopLeft, -5000, -4000));
  b.core->move_absolute(2, -100000);
  while (b.next() != tmcl::kNever && b.last().kind != MotionEventKind::Stopped) {}
  CHECK(b.last().kind == MotionEventKind::Stopped);
  CHECK_EQ(b.get(11, 2), 1);
  CHECK(b.core->position(2) <= -4000);
  CHECK_EQ(b.get(11, 0), 0);
}

TEST(tmcm3351_rfs_makes_the_standing_place_zero) {
  Bench b("tmc4361", "tmcm-3351", 3);
  b.core->move_absolute(1, 5000);
  b.next();
  CHECK_EQ(b.core->position(1), 5000);
  CHECK_EQ(b.core->reference_search(1, tmcl::RfsAction::Start), 0);
  CHECK_EQ(b.core->position(1), 0);
  CHECK_EQ(b.get(0, 1), 0);    // the target too
  CHECK_EQ(b.get(209, 1), 0);  // and the encoder
  CHECK_EQ(b.core->reference_search(1, tmcl::RfsAction::Status), 0);  // no search runs on
}
