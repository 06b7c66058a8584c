// One check for the scenario tests of every input kind: each line must be refused with an error
// that starts with the message given (file, line, column and words), under the options given.
#pragma once

#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "check.hpp"
#include "tmcl/scenario.hpp"

namespace vmtest {

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
