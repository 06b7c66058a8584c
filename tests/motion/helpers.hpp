// Shared helpers of the motion tests: a core on a profile, running to its next event, and
// sampling a plan densely.
#pragma once

#include <cmath>
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

}  // namespace mt
