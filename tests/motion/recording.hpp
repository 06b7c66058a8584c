// A tiny program runner for the motion tests: the motion part of a TMCL program as a list of
// steps, driven through the core API the way tmclrun runs it, with every sample and event
// recorded. Used by the SVG checks (test_plot.cpp) and the golden CSV tool (motion_csv.cpp).
#pragma once

#include <string>

#include "helpers.hpp"
#include "tmcl/motion_plot.hpp"

namespace mt {

struct Runner {
  Bench b;
  tmcl::MotionRecorder rec;
  explicit Runner(const char* core, const char* profile, tmcl::SimTime period) : b(core, profile), rec(1, period) {}
  void advance(tmcl::SimTime t) {
    rec.sample_until(*b.core, t);
    std::size_t n = b.events.size();
    b.to(t);
    for (std::size_t i = n; i < b.events.size(); ++i) rec.motion_event(b.events[i]);
  }
  void wait_pos() {
    while (!b.core->target_reached(0)) advance(b.core->next_event());
  }
  void mvp(std::int32_t target) {
    rec.mark(b.now, 0, tmcl::Mark::MoveIssued, "MVP ABS, 0, " + std::to_string(target), b.core->position(0));
    b.core->move_absolute(0, target);
  }
};

// USB-2-SD manual, section 7.2: SAP 4, 0, 50000 / SAP 5, 0, 10000 / MVP ABS 5000 / WAIT POS /
// MVP ABS 0 / WAIT POS (one pass of the main loop).
inline void usb2sd_main_loop(Runner& r) {
  r.b.set(4, 50000);
  r.b.set(5, 10000);
  r.mvp(5000);
  r.wait_pos();
  r.mvp(0);
  r.wait_pos();
  r.advance(r.b.now + 100000);
}

}  // namespace mt
