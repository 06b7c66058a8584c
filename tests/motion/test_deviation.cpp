// The encoder deviation (212) whatever parts the shaft from the counter (issue 41, 1): a hard
// stop, a timed load of 100 % or more, a load range, mid-plan as at a plan's start, with and
// without stop on stall, on both cores with an encoder (tmc5160 on the TMCM-1260 / PD60-1260,
// tmc429 on the TMCM-1110). The motor stops at the first counter step beyond 212 with the
// `deviation` event and the profile's flag in 207; docs/motion.md, "Shaft and encoder".
// Also what a load range does when the motor turns back (docs/motion.md, "Loads, stalls and lost
// steps"): it resists the shaft moving into it only.
#include <utility>

#include "check.hpp"
#include "helpers.hpp"

using tmcl::MotionEventKind;
using tmcl::SwitchInput;

namespace {

// A TMCM-1260 in pps: 51200 pps (200 fullsteps/s at 256 microsteps), A2 = D2 = 51200 pps².
struct Pd60 : mt::SwitchBench {
  static constexpr std::int32_t kSpeed = 51200;
  Pd60() : SwitchBench("tmc5160", "tmcm-1260", 1) {
    for (auto [param, value] : {std::pair{4, kSpeed}, {5, 51200}, {15, 0}, {16, 0}, {17, 51200}, {18, 51200}, {19, 0},
                                {20, 0}, {140, 8}, {12, 1}, {13, 1}})
      set(param, value);
  }
  static constexpr std::int32_t kFlag = 2;  // 207: "2 deviation error" (manual; reading clears it)
};

// A TMCM-1110 in its units: 1000 at pulse divisor 3 is 30518 pps (119 fullsteps/s at 256).
struct Tmc1110 : mt::SwitchBench {
  static constexpr std::int32_t kSpeed = 1000;
  Tmc1110() : SwitchBench("tmc429", "tmcm-1110", 1) {
    for (auto [param, value] : {std::pair{154, 3}, {153, 7}, {4, kSpeed}, {5, 1000}, {130, 1}, {149, 0}, {140, 8},
                                {12, 1}, {13, 1}})
      set(param, value);
  }
  static constexpr std::int32_t kFlag = 2;
};

// Runs a move to 250000 that something holds at 120000 with 212 = 300: the motor stops at 120301,
// the first step beyond 212, with the deviation event once, 207's flag, 209 where the shaft stands.
template <class B>
void stops_beyond_212(B& b) {
  b.set(212, 300);
  b.core->move_absolute(0, 250000);
  CHECK(b.until(MotionEventKind::Deviation, 40));
  CHECK_EQ(b.core->position(0), 120301);
  CHECK_EQ(b.last().position, 120301);
  CHECK_EQ(b.get(209), 120000);
  CHECK_EQ(b.get(3), 0);  // stopped at once
  CHECK(!b.core->target_reached(0));
  CHECK_EQ(b.get(0), 250000);  // the target kept
  CHECK_EQ(b.get(207) & B::kFlag, B::kFlag);
  CHECK_EQ(b.count(MotionEventKind::StepsLost), 1);  // at the contact, before it
  b.to(b.now + 5000000);
  CHECK_EQ(b.count(MotionEventKind::Deviation), 1);
  CHECK_EQ(b.core->position(0), 120301);
}

template <class B>
void hard_stop_trips_212() {
  B b;
  CHECK(b.core->place_hard_stop(0, SwitchInput::StopRight, 120000));
  stops_beyond_212(b);
}

// A timed load of 150 % mid-move: the shaft stands where it is from then.
template <class B>
void timed_load_trips_212() {
  B b;
  b.set(212, 300);
  b.core->move_absolute(0, 250000);
  b.to(2000000);
  const std::int64_t held = b.core->position(0);
  CHECK(held > 10000 && held < 200000);
  CHECK(b.core->set_load(0, 150));
  CHECK(b.until(MotionEventKind::Deviation, 40));
  CHECK_EQ(b.core->position(0), held + 301);
  CHECK_EQ(b.get(209), held);
  CHECK_EQ(b.count(MotionEventKind::Deviation), 1);
  CHECK_EQ(b.get(207) & B::kFlag, B::kFlag);
}

template <class B>
void load_range_trips_212() {
  B b;
  CHECK(b.core->place_load(0, 120000, 130000, 150));
  stops_beyond_212(b);
}

}  // namespace

TEST(deviation_at_a_hard_stop_tmc5160) { hard_stop_trips_212<Pd60>(); }
TEST(deviation_at_a_hard_stop_tmc429) { hard_stop_trips_212<Tmc1110>(); }
TEST(deviation_under_a_timed_load_tmc5160) { timed_load_trips_212<Pd60>(); }
TEST(deviation_under_a_timed_load_tmc429) { timed_load_trips_212<Tmc1110>(); }
TEST(deviation_in_a_load_range_tmc5160) { load_range_trips_212<Pd60>(); }
TEST(deviation_in_a_load_range_tmc429) { load_range_trips_212<Tmc1110>(); }

namespace {

// With stop on stall: whichever comes first. The machine holds the shaft at 119820, 12 steps past
// a fullstep (256 microsteps, 173 = 0: a measurement each): 212 = 100 trips at 119921, before the
// first measurement after the contact (120064); a wide 212 leaves it to the stall, and the
// deviation never comes.
template <class B>
void with_stop_on_stall(void (*machine)(B&)) {
  for (int wide = 0; wide < 2; ++wide) {
    B b;
    machine(b);
    b.set(173, 0);
    b.set(181, 1);
    b.set(212, wide ? 2000 : 100);
    b.core->move_absolute(0, 250000);
    CHECK(b.until(wide ? MotionEventKind::Stall : MotionEventKind::Deviation, 40));
    const std::int32_t p = b.core->position(0);
    if (wide)
      CHECK(p >= 120064 && p <= 120065);
    else
      CHECK_EQ(p, 119921);
    b.to(b.now + 1000000);
    CHECK_EQ(b.count(MotionEventKind::Stall), wide);
    CHECK_EQ(b.count(MotionEventKind::Deviation), 1 - wide);
  }
}

template <class B>
void hard_stop_near_120000(B& b) {
  CHECK(b.core->place_hard_stop(0, SwitchInput::StopRight, 119820));
}
template <class B>
void range_near_120000(B& b) {
  CHECK(b.core->place_load(0, 119820, 130000, 150));
}

}  // namespace

TEST(deviation_or_stall_at_a_hard_stop) {
  with_stop_on_stall<Pd60>(hard_stop_near_120000<Pd60>);
  with_stop_on_stall<Tmc1110>(hard_stop_near_120000<Tmc1110>);
}
TEST(deviation_or_stall_in_a_load_range) {
  with_stop_on_stall<Pd60>(range_near_120000<Pd60>);
  with_stop_on_stall<Tmc1110>(range_near_120000<Tmc1110>);
}

// A timed load with stop on stall: the stall's measurement or 212, whichever is first. The load
// comes 1 to 100 steps past a fullstep: 212 = 100 trips before the next measurement.
TEST(deviation_or_stall_under_a_timed_load) {
  for (int wide = 0; wide < 2; ++wide) {
    Pd60 b;
    b.set(173, 0);
    b.set(181, 1);
    b.set(212, wide ? 2000 : 100);
    b.core->rotate(0, Pd60::kSpeed);
    CHECK(b.until(MotionEventKind::VelocityReached));
    while (b.core->position(0) % 256 < 1 || b.core->position(0) % 256 > 100) b.to(b.now + 100);
    const std::int32_t p = b.core->position(0);
    CHECK(b.core->set_load(0, 150));
    CHECK(b.until(wide ? MotionEventKind::Stall : MotionEventKind::Deviation, 40));
    if (!wide) CHECK_EQ(b.core->position(0), p + 101);
    b.to(b.now + 1000000);
    CHECK_EQ(b.count(MotionEventKind::Stall), wide);
    CHECK_EQ(b.count(MotionEventKind::Deviation), 1 - wide);
  }
}

// A load lowered before the deviation reaches 212: the shaft follows again, the lost steps stay
// lost, and the deviation the hold had planned does not come.
TEST(deviation_a_load_that_lets_go_in_time) {
  Pd60 b;
  b.set(212, 1000);
  b.core->rotate(0, Pd60::kSpeed);
  CHECK(b.until(MotionEventKind::VelocityReached));
  const std::int32_t p = b.core->position(0);
  CHECK(b.core->set_load(0, 150));
  b.to(b.now + 10000);  // 512 steps at 51200 pps
  CHECK_EQ(b.get(209), p);
  CHECK(b.core->set_load(0, 0));
  const std::int32_t lost = b.core->position(0) - p;
  CHECK(lost >= 511 && lost <= 513);
  b.to(b.now + 1000000);
  CHECK_EQ(b.count(MotionEventKind::Deviation), 0);
  CHECK_EQ(b.get(209), b.core->position(0) - lost);
}

// A range of 150 % holds the shaft at its edge while the motor pushes into it; turning back, the
// shaft leaves the range and follows again (docs/motion.md): 209 moves with the counter, offset by
// the steps lost. A timed load of 150 % holds the shaft whichever way the motor turns.
TEST(load_range_lets_go_when_the_motor_turns_back) {
  Pd60 b;
  CHECK(b.core->place_load(0, 120000, 130000, 150));
  b.core->move_absolute(0, 125000);
  CHECK(b.until(MotionEventKind::TargetReached, 40));
  CHECK_EQ(b.get(209), 120000);  // held at the range's edge: 5000 steps lost
  b.core->move_absolute(0, 100000);
  CHECK(b.until(MotionEventKind::TargetReached, 40));
  CHECK_EQ(b.get(209), 95000);
  b.core->move_absolute(0, 126000);  // into the range again: held at its edge once more
  CHECK(b.until(MotionEventKind::TargetReached, 40));
  CHECK_EQ(b.get(209), 120000);
  CHECK_EQ(b.count(MotionEventKind::StepsLost), 2);

  Pd60 t;
  t.core->move_absolute(0, 10000);
  CHECK(t.until(MotionEventKind::TargetReached, 40));
  CHECK(t.core->set_load(0, 150));
  t.core->move_absolute(0, 0);
  CHECK(t.until(MotionEventKind::TargetReached, 40));
  CHECK_EQ(t.get(209), 10000);  // a brake holds both ways
}
