// The reference search as the manuals describe it where issue 33 found it wrong: the search and
// switch speeds' defaults (item 6) and the inverted home switch, +128 (item 7).
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstdio>
#include <string_view>

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

// Axis parameter 197 on the TMC429 modules that list it: where the reference point was before
// the search made it 0 (errata M31), as on the TMCM-1260 (tmc5160_rfs_modes_1_and_65_one_end_switch).
TEST(tmc429_search_keeps_the_last_reference_position_in_197) {
  for (const char* module : {"tmcm-1140", "tmcm-1160", "tmcm-1161", "tmcm-3110", "tmcm-6110", "tmcm-351"}) {
    g_homing_module = module;
    HomingModule probe;
    const int pd = probe.get(154), rd = probe.get(153);
    mt::Searching<HomingModule> b(800 * pps_per_unit(pd), 200 * pps_per_unit(pd), 600 * pps2_per_unit(pd, rd));
    b.set(4, 800);
    b.set(5, 600);
    b.left_at(-20000);
    b.start();
    b.one_edge(20000);
    if (b.get(197) != -20000) std::fprintf(stderr, "%s: 197 reads %d\n", module, b.get(197));
    CHECK_EQ(b.get(197), -20000);
  }
}

// Item 7: the home switch inverted (+128). A scenario's home range is where the home input reads
// active (high, as parameter 9 reports it); +128 makes the search take the input's other level as
// the switch, so from 0, outside [50000, 60000], every search starts on its (inverted) switch.
// Between end switches at -100000 and +100000 every mode ends, on an edge of the range, and
// turns at an end switch rather than running through it (docs/motion.md, *Reference search*).
namespace {

void inverted_home_search_ends(const char* core, const char* module, int value) {
  mt::SwitchBench b(core, module);
  b.set(193, value);
  b.set(4, std::string_view(core) == "tmc429" ? 2000 : 200000);
  b.left_at(-100000);
  b.right_at(100000);
  b.place(SwitchInput::Home, 50000, 60000);
  b.to(0);
  CHECK_EQ(b.core->reference_search(0, tmcl::RfsAction::Start), 0);
  const bool done = b.until(MotionEventKind::ReferenceDone, 60);
  if (!done) std::fprintf(stderr, "%s %s mode %d: no end (position %d)\n", core, module, value, b.core->position(0));
  CHECK(done);
  // The TMCM-1260 keeps where the reference point was (197): an edge of the home range (modes
  // 5-8), or the end switch's edge (+64: the right one).
  if (std::string_view(module) == "tmcm-1260") {
    const std::int32_t ref = b.get(197);
    const bool ok = value & 128 ? std::abs(ref - 50000) <= 1 || std::abs(ref - 60000) <= 1 : std::abs(ref - 100000) <= 1;
    if (!ok) std::fprintf(stderr, "mode %d: reference point at %d\n", value, ref);
    CHECK(ok);
  }
}

}  // namespace

TEST(inverted_home_every_mode_ends_on_the_pd60_1260) {
  for (int mode : {133, 134, 135, 136, 65, 66, 67, 68}) inverted_home_search_ends("tmc5160", "tmcm-1260", mode);
}

TEST(inverted_home_every_mode_ends_on_the_tmcm_1110) {
  for (int mode = 129; mode <= 136; ++mode) inverted_home_search_ends("tmc429", "tmcm-1110", mode);
}
