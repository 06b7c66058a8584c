// Behaviour of the tmc4361 core through its public API: velocity mode, re-planning mid-move,
// virtual stops, stop switches, encoder deviation, reverse shaft, relative positioning.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>
#include "check.hpp"
#include "helpers.hpp"

using mt::Bench;
using mt::near;
using mt::us;
using tmcl::MotionEventKind;

TEST(velocity_mode_reaches_speed) {
  Bench b;
  b.core->rotate(0, 51200);
  CHECK_EQ(b.next(), 1000000);
  CHECK(b.last().kind == MotionEventKind::VelocityReached);
  CHECK_EQ(b.get(3), 51200);
  CHECK_EQ(b.get(2), 51200);
  CHECK_EQ(b.core->next_event(), tmcl::kNever);
  b.to(2000000);
  CHECK_EQ(b.core->position(0), 25600 + 51200);
}

TEST(velocity_mode_s_curve) {
  Bench b;
  b.set(14, 1);
  b.core->rotate(0, -51200);
  CHECK_EQ(b.next(), 1100000);  // V/A + A/J
  CHECK_EQ(b.get(3), -51200);
}

TEST(velocity_reversal_passes_zero_once) {
  for (int s = 0; s <= 1; ++s) {
    Bench b;
    b.set(14, s);
    b.core->rotate(0, 51200);
    b.next();
    b.core->rotate(0, -51200);
    tmcl::SimTime start = b.now, end = b.core->next_event();
    CHECK_EQ(end - start, s ? 2200000 : 2000000);
    int changes = 0;
    double prev = 1;
    for (tmcl::SimTime t = start; t <= end; t += 100) {
      double v = b.core->sample_at(0, t).velocity;
      if ((v < 0) != (prev < 0)) ++changes;
      prev = v;
    }
    CHECK_EQ(changes, 1);
    b.next();
    CHECK(b.last().kind == MotionEventKind::VelocityReached);
  }
}

TEST(mst_is_a_soft_stop) {
  Bench b;
  b.core->rotate(0, 51200);
  b.next();
  b.core->stop(0);
  CHECK_EQ(b.next(), 2000000);
  CHECK(b.last().kind == MotionEventKind::Stopped);
  CHECK_EQ(b.core->position(0), 25600 + 25600);
  CHECK_EQ(b.get(3), 0);
  b.core->stop(0);  // at rest: nothing happens
  CHECK_EQ(b.core->next_event(), tmcl::kNever);
}

TEST(new_target_ahead_extends_move) {
  Bench b;
  b.core->move_absolute(0, 100000);
  b.to(1000000);
  b.core->move_absolute(0, 200000);
  CHECK_EQ(b.next(), us(1 + (200000.0 - 25600 - 25600) / 51200 + 1));
  CHECK_EQ(b.core->position(0), 200000);
}

TEST(new_target_too_close_overshoots_and_returns) {
  Bench b;
  b.core->move_absolute(0, 100000);
  b.to(1000000);  // at 25600 with 51200 pps: needs 25600 steps to stop
  b.core->move_absolute(0, 30000);
  tmcl::SimTime end = b.core->next_event();
  std::int64_t far = 0;
  for (tmcl::SimTime t = b.now; t <= end; t += 100) far = std::max(far, b.core->sample_at(0, t).position);
  CHECK_EQ(far, 51200);
  CHECK_EQ(b.next(), us(2 + 2 * std::sqrt(21200.0 / 51200)));
  CHECK_EQ(b.core->position(0), 30000);
  CHECK(b.last().kind == MotionEventKind::TargetReached);
}

TEST(target_behind_reverses) {
  Bench b;
  b.core->move_absolute(0, 100000);
  b.to(1000000);
  b.core->move_absolute(0, 0);  // stop at 51200 (t = 2 s), then 51200 back: 1 + 1 s, no cruise
  CHECK_EQ(b.next(), us(2 + 2));
  CHECK_EQ(b.core->position(0), 0);
}

TEST(lower_vmax_mid_move) {
  Bench b;
  b.core->move_absolute(0, 100000);
  b.to(1000000);
  b.set(4, 25600);
  tmcl::SimTime end = b.core->next_event();
  CHECK_EQ(end, us(1 + 0.5 + 48800.0 / 25600 + 0.5));
  CHECK(near(b.core->sample_at(0, 2000000).velocity, 25600));
  b.next();
  CHECK_EQ(b.core->position(0), 100000);
}

TEST(change_acceleration_mid_move) {
  Bench b;
  b.core->move_absolute(0, 100000);
  b.to(500000);
  b.set(5, 25600);
  CHECK_EQ(b.next(), us(0.5 + 1 + 4000.0 / 51200 + 2));
}

TEST(same_parameter_value_does_not_replan) {
  Bench b;
  b.set(14, 1);
  b.core->move_absolute(0, 100000);
  b.to(700000);
  b.set(4, 51200);
  b.set(22, 512000);
  CHECK_EQ(b.next(), us(3.053125));
}

TEST(s_curve_replan_mid_acceleration_is_continuous) {
  Bench b;
  b.set(14, 1);
  b.core->move_absolute(0, 100000);
  b.to(50000);  // inside B1, a > 0
  auto before = b.core->sample_at(0, 50000);
  b.core->move_absolute(0, 3000);  // cannot make it: overshoot and come back
  auto after = b.core->sample_at(0, 50000);
  CHECK(near(before.velocity, after.velocity));
  CHECK(near(before.acceleration, after.acceleration));
  b.next();
  CHECK_EQ(b.core->position(0), 3000);
  CHECK(b.last().kind == MotionEventKind::TargetReached);
}

TEST(virtual_stop_hard) {
  Bench b;
  b.set(27, 50000);
  b.set(28, 2);
  b.set(29, 1);
  b.core->move_absolute(0, 100000);
  CHECK_EQ(b.next(), us(1 + 24400.0 / 51200));
  CHECK(b.last().kind == MotionEventKind::Stopped);
  CHECK_EQ(b.core->position(0), 50000);
  CHECK_EQ(b.get(0), 100000);  // the target stays
  CHECK_EQ(b.get(8), 0);
  b.core->move_absolute(0, 100000);  // blocked in that direction
  b.next();
  CHECK(b.last().kind == MotionEventKind::Stopped);
  CHECK_EQ(b.core->position(0), 50000);
  b.core->move_absolute(0, 0);  // the other way is free
  b.next();
  CHECK(b.last().kind == MotionEventKind::TargetReached);
  CHECK_EQ(b.core->position(0), 0);
}

TEST(virtual_stop_soft_with_stop_deceleration) {
  Bench b;
  b.set(27, 50000);
  b.set(28, 2);
  b.set(29, 2);
  b.set(21, 51200);
  b.core->move_absolute(0, 100000);
  CHECK_EQ(b.next(), us(2 + 24400.0 / 51200));
  CHECK_EQ(b.core->position(0), 75600);  // beyond the stop by v^2 / (2 DSTOP)
}

TEST(virtual_stop_soft_is_linear_on_s_curve) {
  Bench b;
  b.set(14, 1);
  b.set(26, -50000);
  b.set(28, 1);
  b.set(29, 2);
  b.set(21, 102400);
  b.core->rotate(0, -51200);
  b.next();  // velocity reached at 1.1 s
  tmcl::SimTime t = b.next();
  CHECK(b.last().kind == MotionEventKind::Stopped);
  // linear stop: the acceleration is exactly DSTOP during the stop
  CHECK(near(b.core->sample_at(0, t - 100000).acceleration, 102400));
  CHECK(b.core->position(0) <= -62799 && b.core->position(0) >= -62801);  // 51200^2 / (2 DSTOP)
}

TEST(virtual_stop_normal_ramp_mode) {
  Bench b;
  b.set(27, 50000);
  b.set(28, 2);
  b.set(29, 0);  // normal deceleration settings
  b.set(17, 25600);
  b.core->move_absolute(0, 200000);  // at full speed when it meets the stop
  b.next();
  CHECK(b.last().kind == MotionEventKind::Stopped);
  CHECK_EQ(b.core->position(0), 50000 + 51200);  // 51200^2 / (2 * 25600)
}

TEST(stop_switch_hard_and_soft) {
  {
    Bench b;
    b.core->move_absolute(0, 100000);
    b.to(500000);
    b.core->set_switch(0, tmcl::SwitchInput::StopRight, true);
    CHECK_EQ(b.next(), 500000);
    CHECK(b.last().kind == MotionEventKind::Stopped);
    CHECK_EQ(b.core->position(0), 6400);
    b.core->move_absolute(0, 100000);
    b.next();
    CHECK_EQ(b.core->position(0), 6400);  // blocked while the switch is active
    b.core->move_absolute(0, 0);
    b.next();
    CHECK_EQ(b.core->position(0), 0);
  }
  {
    Bench b;
    b.set(21, 51200);
    b.core->move_absolute(0, 100000);
    b.to(500000);
    b.core->set_switch(0, tmcl::SwitchInput::StopRight, true);
    CHECK_EQ(b.next(), 1000000);
    CHECK_EQ(b.core->position(0), 12800);
  }
  {
    Bench b;  // the left switch does not stop a motor moving right
    b.core->move_absolute(0, 1000);
    b.core->set_switch(0, tmcl::SwitchInput::StopLeft, true);
    b.next();
    CHECK(b.last().kind == MotionEventKind::TargetReached);
  }
}

TEST(encoder_follows_and_slip_trips_deviation) {
  Bench b;
  b.set(212, 100);
  b.core->move_absolute(0, 100000);
  b.to(500000);
  CHECK_EQ(b.get(209), 6400);
  b.core->encoder_slip(0, -200);
  CHECK_EQ(b.next(), 500000);
  CHECK(b.last().kind == MotionEventKind::Deviation);
  CHECK_EQ(b.core->position(0), 6400);
  CHECK_EQ(b.get(209), 6200);
  CHECK_EQ(b.get(207), 2);
  CHECK_EQ(b.get(207), 0);  // cleared by reading
  b.set(209, 6400);         // re-align the encoder: motion is possible again
  b.core->move_absolute(0, 10000);
  b.next();
  CHECK(b.last().kind == MotionEventKind::TargetReached);
}

TEST(encoder_resolution_scales_slip) {
  Bench b;
  b.set(210, 4000);  // 4000 counts per turn, 51200 microsteps per turn: 12.8 per count
  b.core->encoder_slip(0, 10);
  CHECK_EQ(b.get(209), 128);
}

TEST(reverse_shaft_reverses_encoder_relation) {
  Bench b;
  b.set(251, 1);
  b.core->move_absolute(0, 1000);
  b.next();
  CHECK_EQ(b.get(209), -1000);
  b.set(210, -51200);  // count the other way: the encoder agrees again
  CHECK_EQ(b.get(209), -1000);
  b.set(209, 1000);
  b.set(212, 100);
  b.core->move_absolute(0, 5000);
  b.next();
  CHECK(b.last().kind == MotionEventKind::TargetReached);
  CHECK_EQ(b.get(209), 5000);
}

TEST(reversed_encoder_trips_by_position) {
  Bench b;
  b.set(251, 1);
  b.set(212, 100);
  b.core->move_absolute(0, 1000);
  b.next();
  CHECK(b.last().kind == MotionEventKind::Deviation);
  CHECK_EQ(b.core->position(0), 51);  // |X - (-X)| = 2X > 100
}

TEST(relative_positioning_option) {
  Bench b;
  b.core->move_absolute(0, 1000);
  b.to(10000);                     // still moving
  b.core->move_relative(0, 500);   // 127 = 0: from the last target
  CHECK_EQ(b.get(0), 1500);
  b.next();
  b.set(127, 1);
  b.set(1, 20);                    // actual position 20, target stays 1500
  b.core->move_relative(0, 5);
  CHECK_EQ(b.get(0), 25);
  b.next();
  b.set(127, 2);
  b.set(209, 100);
  b.core->move_relative(0, 5);
  CHECK_EQ(b.get(0), 105);
}

TEST(write_actual_position_mid_move_keeps_target) {
  Bench b;
  b.core->move_absolute(0, 100000);
  b.to(1000000);
  b.set(1, 0);  // the motor was at 25600: now 0, still heading for 100000
  b.next();
  CHECK_EQ(b.core->position(0), 100000);
  CHECK(b.last().kind == MotionEventKind::TargetReached);
}

TEST(move_to_current_position_reports_at_once) {
  Bench b;
  b.core->move_absolute(0, 0);
  CHECK_EQ(b.core->next_event(), 0);
  b.next();
  CHECK(b.last().kind == MotionEventKind::TargetReached);
}

TEST(zero_acceleration_never_moves) {
  Bench b;
  b.set(5, 0);
  b.core->move_absolute(0, 1000);
  CHECK_EQ(b.core->next_event(), tmcl::kNever);
  CHECK_EQ(b.get(8), 0);
}

TEST(read_only_and_ranges) {
  Bench b;
  CHECK(b.core->set_param(0, 3, 5) == tmcl::ParamWrite::ReadOnly);
  CHECK(b.core->set_param(0, 14, 2) == tmcl::ParamWrite::OutOfRange);
  CHECK(b.core->set_param(0, 35, 0) == tmcl::ParamWrite::OutOfRange);
  CHECK(b.core->owns(202) && !b.core->owns(6));
  CHECK_EQ(b.get(202), 200);
  CHECK_EQ(b.get(8), 1);
}

TEST(registry_names) {
  auto names = tmcl::motion_core_names();
  CHECK(std::find(names.begin(), names.end(), "tmc4361") != names.end());
  CHECK(std::find(names.begin(), names.end(), "linear") != names.end());
  CHECK_EQ(tmcl::find_profile("usb-2-sd")->default_motion, std::string_view("tmc4361"));
  CHECK_EQ(tmcl::find_profile("tmc2300-eval")->default_motion, std::string_view("linear"));
}

// The registry is motion_cores.def: every core file vm/motion/motion_NAME.cpp is a core named
// NAME, made by its name, and nothing else is built in.
TEST(registry_is_the_core_files) {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(TMCL_MOTION_DIR)) {
    const std::string f = e.path().filename().string();
    if (f.rfind("motion_", 0) == 0 && e.path().extension() == ".cpp") files.push_back(e.path().stem().string().substr(7));
  }
  std::sort(files.begin(), files.end());
  CHECK(files.size() >= 5u);
  CHECK(files == tmcl::motion_core_names());
  for (const auto& name : files) {
    auto core = tmcl::make_motion_core(name);
    CHECK(core != nullptr);
    if (core) CHECK_EQ(core->name(), std::string_view(name));
  }
}

TEST(two_motors_events_in_time_order) {
  Bench b("tmc4361", "generic", 2);
  b.core->move_absolute(0, 100000);
  b.core->move_absolute(1, 10000);
  b.to(5000000);
  CHECK_EQ(b.events.size(), std::size_t{2});
  CHECK_EQ(b.events[0].motor, 1);
  CHECK_EQ(b.events[1].motor, 0);
}

// RFS START on the ramp cores (offered by the generic profile): the motor stops where it is,
// that place becomes position and target 0 (encoder 0 too on tmc4361), the search is done at
// once and reported by the next advance, and the motor then stays at rest.
TEST(reference_search_zeroes_where_the_motor_is) {
  for (const char* name : {"tmc4361", "linear"}) {
    mt::Bench b(name, "generic");
    b.core->move_absolute(0, 100000);
    b.to(200000);  // 0.2 s into the move
    std::int32_t moved = b.core->position(0);
    CHECK(moved > 0);
    b.core->reference_search(0, tmcl::RfsAction::Start);
    b.to(200000);
    CHECK(!b.events.empty() && b.last().kind == tmcl::MotionEventKind::ReferenceDone);
    CHECK_EQ(b.core->position(0), 0);
    CHECK_EQ(b.get(0), 0);
    CHECK(b.core->target_reached(0));
    CHECK(b.core->reference_done(0));
    if (std::string(name) == "tmc4361") CHECK_EQ(b.get(209), 0);
    CHECK_EQ(b.core->next_event(), tmcl::kNever);  // nothing more happens
    b.to(5000000);
    CHECK_EQ(b.core->position(0), 0);
  }
}
