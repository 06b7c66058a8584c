// The motion cores against every module profile: the profile is the only source of a
// parameter's range, default and access, so a core that owns a parameter must start at the
// profile's default and accept the profile's whole range. For every core and every profile
// (generic, which accepts every number, aside): each owned parameter the profile lists powers
// up at the profile's default (writable ones; the core computes the read-only ones), and the
// profile's minimum and maximum are accepted.
#include <string>
#include <utility>

#include "check.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"

TEST(motion_cores_agree_with_every_profile) {
  int checked = 0;
  for (const tmcl::Profile* p : tmcl::all_profiles()) {
    if (p->any_parameter) continue;
    for (const auto& name : tmcl::motion_core_names()) {
      for (const auto& info : p->axis_params) {
        auto core = tmcl::make_motion_core(name);
        core->reset(*p, p->motors);
        if (!core->owns(info.number)) continue;
        const std::string what = name + " on " + std::string(p->name) + ", axis parameter " + std::to_string(info.number);
        ++checked;
        if (!(info.access & tmcl::kWrite)) continue;  // read-only: the core computes it
        if (core->get_param(0, info.number) != info.default_value)
          CHECK_EQ(what + ": default " + std::to_string(core->get_param(0, info.number)),
                   what + ": default " + std::to_string(info.default_value));
        for (std::int64_t v : {info.min, info.max}) {
          if (v < INT32_MIN || v > INT32_MAX) continue;
          auto r = core->set_param(0, info.number, static_cast<std::int32_t>(v));
          if (r != tmcl::ParamWrite::Ok)
            CHECK_EQ(what + ": " + std::to_string(v) + " refused", what + ": " + std::to_string(v) + " accepted");
        }
      }
    }
  }
  CHECK(checked > 20);
}

// A parameter another module's profile does not list starts at the default of the profile of
// the module the core models (tmc4361: usb-2-sd, linear: tmc2300-eval): no core keeps its own.
TEST(motion_cores_take_missing_defaults_from_their_home_profile) {
  const tmcl::Profile* usb = tmcl::find_profile("usb-2-sd");
  const tmcl::Profile* tmc = tmcl::find_profile("tmc2300-eval");
  CHECK(usb && tmc);
  if (!usb || !tmc) return;
  auto ramp = tmcl::make_motion_core("tmc4361");
  ramp->reset(*tmc, 1);
  CHECK(!tmc->axis_param(22));
  CHECK_EQ(ramp->get_param(0, 22), usb->axis_param(22)->default_value);  // bow 1
  CHECK_EQ(ramp->get_param(0, 202), usb->axis_param(202)->default_value);  // full steps
  auto linear = tmcl::make_motion_core("linear");
  linear->reset(*usb, 1);
  CHECK(!usb->axis_param(6));
  CHECK_EQ(linear->get_param(0, 6), tmc->axis_param(6)->default_value);  // run current
}

// Under the generic profile the VM checks no range, so a core checks a write against the row of
// the module it models (tmc4361 and ideal: usb-2-sd, linear: tmc2300-eval), the same rows that
// give its defaults: every writable owned parameter takes its row's minimum and maximum and
// refuses one beyond either. No core keeps a range table of its own (vm/motion/core_skeleton.hpp).
TEST(motion_cores_check_their_home_rows_under_the_generic_profile) {
  const tmcl::Profile* generic = tmcl::find_profile("generic");
  CHECK(generic && generic->any_parameter);
  if (!generic) return;
  const std::pair<const char*, const char*> cores[] = {{"tmc4361", "usb-2-sd"}, {"ideal", "usb-2-sd"}, {"linear", "tmc2300-eval"}};
  int checked = 0;
  for (const auto& [name, home_name] : cores) {
    const tmcl::Profile* home = tmcl::find_profile(home_name);
    CHECK(home != nullptr);
    if (!home) continue;
    for (const auto& info : home->axis_params) {
      auto core = tmcl::make_motion_core(name);
      core->reset(*generic, 1);
      // 0 and 2 start moves, 1 and 209 set positions: every 32-bit value is a position or speed
      if (!core->owns(info.number) || !(info.access & tmcl::kWrite) || info.number <= 2 || info.number == 209) continue;
      const std::string what = std::string(name) + " under generic, axis parameter " + std::to_string(info.number);
      for (std::int64_t v : {info.min, info.max}) {
        if (v < INT32_MIN || v > INT32_MAX) continue;
        if (core->set_param(0, info.number, static_cast<std::int32_t>(v)) != tmcl::ParamWrite::Ok)
          CHECK_EQ(what + ": " + std::to_string(v) + " refused", what + ": " + std::to_string(v) + " accepted");
      }
      for (std::int64_t v : {info.min - 1, info.max + 1}) {
        if (v < INT32_MIN || v > INT32_MAX) continue;
        ++checked;
        if (core->set_param(0, info.number, static_cast<std::int32_t>(v)) != tmcl::ParamWrite::OutOfRange)
          CHECK_EQ(what + ": " + std::to_string(v) + " accepted", what + ": " + std::to_string(v) + " refused");
      }
    }
  }
  CHECK(checked > 30);
  // The speed limit of the linear core is the top of its row too: ROR beyond it is clipped.
  auto linear = tmcl::make_motion_core("linear");
  linear->reset(*generic, 1);
  linear->rotate(0, 40000);
  CHECK_EQ(linear->get_param(0, 2), 32767);
}
