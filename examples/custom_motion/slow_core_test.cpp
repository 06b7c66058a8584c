// Registers the example `slow` core and checks it through the registry, the way tmclrun
// --motion slow would use it.
#define TMCL_TEST_MAIN
#include "check.hpp"
#include "slow_core.hpp"
#include "tmcl/profile.hpp"

TEST(slow_core_registers_and_moves) {
  tmcl::register_motion_core("slow", make_slow_motion_core);
  auto names = tmcl::motion_core_names();
  CHECK(std::find(names.begin(), names.end(), "slow") != names.end());
  auto core = tmcl::make_motion_core("slow");
  CHECK(core != nullptr);
  core->reset(*tmcl::find_profile("tmc2300-eval"), 1);  // speed 10000 pps from parameter 4's default
  core->move_absolute(0, 25000);
  CHECK_EQ(core->next_event(), 2500000);
  std::vector<tmcl::MotionEvent> ev;
  core->advance(1000000, ev);
  CHECK(ev.empty());
  CHECK_EQ(core->position(0), 10000);
  CHECK(!core->target_reached(0));
  CHECK_EQ(core->sample_at(0, 2000000).position, 20000);
  core->advance(2500000, ev);
  CHECK_EQ(ev.size(), std::size_t{1});
  CHECK(ev[0].kind == tmcl::MotionEventKind::TargetReached);
  CHECK_EQ(core->position(0), 25000);
  CHECK(core->target_reached(0));
  CHECK(core->set_param(0, 4, 3) == tmcl::ParamWrite::Ok);
  core->move_absolute(0, 25010);  // 10 steps at 3 pps: 3.333.. s, rounded up
  CHECK_EQ(core->next_event(), 2500000 + 3333334);
}
