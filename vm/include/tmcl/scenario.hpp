// Scenarios: timed changes of the world outside the program (tmclrun --scenario FILE).
//
//   # comment; blank lines are ignored
//   at 10ms  input 0 = 1        digital input 0 (GIO 0, 0)
//   at 1s    analog 2 = 512     analog input 2 (GIO 2, 1)
//   at 2s    left 0 = 1         left stop switch of motor 0 (interrupt 27, WAIT LIMSW)
//   at 2s    right 0 = 1        right stop switch of motor 0 (interrupt 28, WAIT LIMSW)
//   at 2500ms home 0 = 1        reference (home) switch of motor 0 (WAIT REFSW)
//   at 3s    slip 0 = -400      the encoder of motor 0 loses 400 counts (deviation check)
// Times are absolute simulated instants (durations as in duration.hpp); events at the same
// instant apply in file order. A bad line is reported as FILE:LINE: error: ... .
#pragma once

#include <string>
#include <vector>

#include "tmcl/vm.hpp"

namespace tmcl {

bool parse_scenario(const std::string& text, const std::string& file, std::vector<InputEvent>& out,
                    std::string& error);

}  // namespace tmcl
