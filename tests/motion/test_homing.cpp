// The reference search as the manuals describe it where issue 33 found it wrong: the search and
// switch speeds' defaults (item 6) and the inverted home switch, +128 (item 7).
#include <cmath>
#include <cstdint>

#include "check.hpp"
#include "helpers.hpp"

using tmcl::MotionEventKind;
using tmcl::SwitchInput;

namespace {

double pps_per_unit(int pulse_div) { return std::ldexp(16e6, -(pulse_div + 16)); }
double pps2_per_unit(int pulse_div, int ramp_div) { return std::ldexp(16e6 * 16e6, -(pulse_div + ramp_div + 29)); }

// The tmc429 core on the module a test names (Searching default-constructs its bench).
const char* g_homing_module = "tmcm-1110";
struct HomingModule : mt::SwitchBench {
  HomingModule() : SwitchBench("tmc429", g_homing_module) {}
};

}  // namespace

// TMCM-1110 manual 5.3 (and the TMCM-351's and the TMCL reference's hints): "the searching speed
// is identical to the maximum positioning speed (axis parameter 4), unless reduced by axis
// parameter 194", "this low calibrating speed is a quarter of the maximum positioning speed by
// default (axis parameter 195)". A mode-1 search on each TMC429 module with only 4 and 5 set
// runs at 4 to the switch and at 4 / 4 out of it and back (errata M16).
TEST(tmc429_search_with_only_4_and_5_set_runs_at_4_and_a_quarter_of_it) {
  for (const char* module : {"tmcm-1110", "tmcm-1140", "tmcm-1160", "tmcm-1161", "tmcm-3110", "tmcm-6110", "tmcm-351"}) {
    g_homing_module = module;
    HomingModule probe;
    const int pd = probe.get(154), rd = probe.get(153);
    mt::Searching<HomingModule> b(800 * pps_per_unit(pd), 200 * pps_per_unit(pd), 600 * pps2_per_unit(pd, rd));
    CHECK_EQ(b.get(194), 0);
    CHECK_EQ(b.get(195), 0);
    CHECK_EQ(b.get(149), 0);  // hard stops at the switch, as Searching counts
    b.set(4, 800);
    b.set(5, 600);
    b.left_at(-20000);
    b.start();
    b.one_edge(20000);
  }
}
