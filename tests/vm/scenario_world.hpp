// What the scenario tests of every input kind share: a machine with a core by name, a profile and
// a scenario (World), and one check that each line of a list is refused with an error that starts
// with the message given (file, line, column and words).
#pragma once

#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "check.hpp"
#include "machine.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/scenario.hpp"

namespace vmtest {

// A machine (generic profile unless one is given) with a core by name, running `prog` from 0
// with `scenario`'s inputs.
struct World {
  std::unique_ptr<tmcl::MotionCore> core;
  tmcl::Vm vm;
  World(const char* core_name, const tmcl::Profile& profile, const std::vector<tmcl::Instruction>& prog,
        const std::string& scenario)
      : core(tmcl::make_motion_core(core_name)), vm(profile, *core) {
    vm.instr_time = 20;
    vm.load(prog);
    vm.power_on(nullptr);
    std::vector<tmcl::InputEvent> ev;
    std::string err;
    CHECK(tmcl::parse_scenario(scenario, "s.txt", ev, err));
    CHECK_EQ(err, std::string());
    vm.add_inputs(ev);
    vm.start(0);
  }
  World(const char* core_name, const std::vector<tmcl::Instruction>& prog, const std::string& scenario)
      : World(core_name, tmcl::generic_profile(), prog, scenario) {}
};

struct ScenarioError {
  const char* line;
  const char* message;
};

inline void expect_scenario_errors(std::span<const ScenarioError> cases, const tmcl::ScenarioOptions& opts) {
  for (const auto& c : cases) {
    std::vector<tmcl::InputEvent> ev;
    std::string err;
    CHECK(!tmcl::parse_scenario(std::string(c.line) + "\n", "s.txt", ev, err, opts));
    if (err.rfind(c.message, 0) != 0) std::fprintf(stderr, "%s\n  gave: %s\n", c.line, err.c_str());
    CHECK(err.rfind(c.message, 0) == 0);
  }
}

}  // namespace vmtest
