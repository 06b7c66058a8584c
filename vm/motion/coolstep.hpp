// coolStep's current regulation as the TMCM modules' manuals give it (TMCM-1110 manual 5 and 5.2,
// PD57/60-1260 manual 4 and 7.3; docs/motion.md, "coolStep"): at each stallGuard2 measurement
// while coolStep is on, the actual current scale (axis parameter 180, 0..31: 1/32 .. 32/32 of full
// scale) goes up by the up step (171: 1, 2, 4, 8) when the load value is below the lower threshold
// 172 · 32, and down by one after every so many measurements (169: 32, 8, 2, 1) above the upper
// threshold (172 + 170 + 1) · 32; never above the run current's scale (6) nor below its half or
// quarter (168). 172 = 0 switches coolStep off (TMC262 and TMC5160 datasheets: SEMIN = 0; the
// stepRocker's open firmware leaves it off then). Where the manuals are silent: docs/errata.md
// E70-E72.
#pragma once

#include <algorithm>
#include <cstdint>

namespace tmcl::coolstep {

// The settings, as the parameters hold them.
struct Settings {
  int run = 31;     // the run current 6 as a current scale 0..31
  int seimin = 0;   // 168: 0 -> 1/2 of the run current, 1 -> 1/4
  int sedn = 0;     // 169: measurements above the upper threshold per decrement, 0..3 -> 32, 8, 2, 1
  int semax = 0;    // 170: the upper threshold's distance from the lower one, in 32s
  int seup = 0;     // 171: 0..3 -> up steps of 1, 2, 4, 8
  int semin = 0;    // 172: the lower threshold in 32s; 0: coolStep off
};

inline bool enabled(const Settings& s) { return s.semin > 0; }
inline int lower(const Settings& s) { return s.semin * 32; }
inline int upper(const Settings& s) { return (s.semin + s.semax + 1) * 32; }
// The least scale: (run + 1)/32 halved or quartered, as a scale (E70): 31 -> 15 or 7.
inline int minimum(const Settings& s) { return std::max(0, (s.run + 1) / (s.seimin ? 4 : 2) - 1); }
inline int up_step(const Settings& s) { return 1 << std::clamp(s.seup, 0, 3); }
inline int down_after(const Settings& s) {
  constexpr int kCounts[] = {32, 8, 2, 1};
  return kCounts[std::clamp(s.sedn, 0, 3)];
}

// The regulation's state: the actual scale and the measurements above the upper threshold in a
// row since the last decrement (E70: one in the band or below starts the count again).
struct State {
  int cs = 31;
  int above = 0;
  bool operator==(const State&) const = default;
};

// The state at the start of regulation, and whenever it stops: the run current (E71).
inline State start(const Settings& s) { return {s.run, 0}; }

// One measurement `value` (206) while coolStep is on: the state after it.
inline State measure(State st, const Settings& s, int value) {
  if (value < lower(s)) {
    st.above = 0;
    st.cs = std::min(s.run, st.cs + up_step(s));
  } else if (value >= upper(s)) {
    if (st.cs <= minimum(s)) {
      st.above = 0;  // nothing to decrement: the count does not run on (E70)
    } else if (++st.above >= down_after(s)) {
      st.above = 0;
      --st.cs;
    }
  } else {
    st.above = 0;
  }
  st.cs = std::max(st.cs, std::min(minimum(s), s.run));
  return st;
}

}  // namespace tmcl::coolstep
