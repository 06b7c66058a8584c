// MVP REL on every built-in core (issue 33, item 1): the new target is the actual position + the
// offset (TMCL reference, MVP; TMCM-1110 manual 4.5.4; TMC2300-MOTOR-EVAL manual, MVP), except on a
// module whose profile has axis parameter 127 (USB-2-SD, TMCM-1260), which follows 127 as set.
// One rule in core_skeleton.hpp; these tests run it through each core's public API, after a
// rotation stopped away from the last target and during a positioning under way.
#include <cstdint>

#include "check.hpp"
#include "helpers.hpp"

using mt::Bench;

namespace {

// Rotates, stops, and waits until the motor is at rest away from the last target (0); returns
// where it stopped.
std::int32_t rotate_and_stop(Bench& b, std::int32_t speed) {
  b.core->rotate(0, speed);
  b.to(b.now + 500'000);
  b.core->stop(0);
  for (int i = 0; i < 10 && b.next() != tmcl::kNever;) ++i;
  b.to(b.now + 1'000'000);
  const std::int32_t at = b.core->position(0);
  CHECK(at != 0);
  return at;
}

// A core on a module without 127: MVP REL counts from the actual position, after a rotation and
// during an MVP ABS under way (`ramps`: an ideal motor is never under way, it jumps).
void counts_from_the_actual_position(const char* core, const char* profile, std::int32_t speed, bool ramps = true) {
  Bench b(core, profile);
  const std::int32_t stopped = rotate_and_stop(b, speed);
  b.core->move_relative(0, 1000);
  CHECK_EQ(b.get(0), stopped + 1000);
  if (!ramps) return;
  b.core->move_absolute(0, stopped + 1'000'000);
  b.to(b.now + 200'000);  // under way
  const std::int32_t now = b.core->position(0);
  CHECK(now != stopped && now != stopped + 1'000'000);
  b.core->move_relative(0, 1000);
  CHECK_EQ(b.get(0), now + 1000);
}

}  // namespace

TEST(mvp_rel_counts_from_the_actual_position_on_the_tmc429_modules) {
  counts_from_the_actual_position("tmc429", "tmcm-1110", 500);
  counts_from_the_actual_position("tmc429", "tmcm-3110", 500);
}

TEST(mvp_rel_counts_from_the_actual_position_on_the_tmc2300_eval) {
  counts_from_the_actual_position("linear", "tmc2300-eval", 5000);
}

TEST(mvp_rel_counts_from_the_actual_position_on_any_core_without_127) {
  counts_from_the_actual_position("ideal", "tmcm-1110", 5000, false);
  counts_from_the_actual_position("tmc4361", "tmc2300-eval", 5000);
  counts_from_the_actual_position("tmc5160", "tmcm-1110", 5000);
  // Under generic the module the core models decides: the TMCM-1110 (tmc429) has no 127.
  counts_from_the_actual_position("tmc429", "generic", 500);
}

// Where the module has 127 it decides. The TMCM-1260: 0 (the default) from the last target, 1
// from the actual position, on its core, its fallback and ideal; the USB-2-SD: 0 the last
// target, 1 the actual position, 2 the encoder position.
TEST(mvp_rel_follows_127_where_the_module_has_it) {
  for (const char* core : {"tmc5160", "linear", "ideal"}) {  // the module's core, its fallback, ideal
    Bench b(core, "tmcm-1260");
    CHECK(b.core->owns(127));
    CHECK_EQ(b.get(127), 0);
    const std::int32_t stopped = rotate_and_stop(b, 5000);
    b.core->move_relative(0, 1000);
    CHECK_EQ(b.get(0), 1000);
    b.core->move_absolute(0, stopped);
    for (int i = 0; i < 10 && b.next() != tmcl::kNever;) ++i;
    b.set(127, 1);
    b.core->rotate(0, 5000);
    b.to(b.now + 300'000);
    b.core->stop(0);
    for (int i = 0; i < 10 && b.next() != tmcl::kNever;) ++i;
    const std::int32_t again = b.core->position(0);
    CHECK(again != stopped);
    b.core->move_relative(0, 1000);
    CHECK_EQ(b.get(0), again + 1000);
    CHECK(b.core->set_param(0, 127, 2) == tmcl::ParamWrite::OutOfRange);  // 0..1 on this module
  }
  for (int option : {0, 1, 2}) {
    Bench b("tmc4361", "usb-2-sd");
    b.set(127, option);
    const std::int32_t stopped = rotate_and_stop(b, 5000);
    b.set(209, stopped + 77);
    b.core->move_relative(0, 1000);
    CHECK_EQ(b.get(0), (option == 0 ? 0 : option == 1 ? stopped : stopped + 77) + 1000);
  }
}
