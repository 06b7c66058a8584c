// Scenarios: timed changes of the world outside the program (tmclrun --scenario FILE).
//
//   # comment; blank lines are ignored
//   at 10ms  input 0 = 1        digital input 0 (GIO 0, 0)
//   at 1s    analog 2 = 512     analog input 2 (GIO 2, 1); with a profile, any analog input
//                               it lists (analog 8 = 240: the TMCM-1260's supply voltage)
//   at 2s    left 0 = 1         left stop switch of motor 0 (interrupt 27, WAIT LIMSW)
//   at 2s    right 0 = 1        right stop switch of motor 0 (interrupt 28, WAIT LIMSW)
//   at 2500ms home 0 = 1        reference (home) switch of motor 0 (WAIT REFSW)
//   at 3s    slip 0 = -400      motor 0's encoder / shaft slips by 400 (deviation check, 212);
//                               refused where the core models no encoder (ScenarioOptions)
//   switch left 0 at -20000         closed while motor 0's position is <= -20000
//   switch right 0 at 30000         closed while motor 0's position is >= 30000
//   switch home 0 from -150 to 150  closed while the position is in the range (left and right
//                                   take a range too: a cam on that input)
//   hardstop left 0 at -21000       a mechanical end: motor 0's shaft cannot go below -21000
//   hardstop right 0 at 31000       ... nor above 31000 (it may lie inside a switch's range)
//   at 4s    load 0 = 60%           from 4 s on a load of 60 % of the holding torque (100 % and
//                                   above: the motor stalls), until the next such line
//   load 0 from 5000 to 6000 = 80%  a load while the shaft is between the positions (a clamp)
// Switches, hard stops and loads at positions belong to the machine: the position is the motor's physical one, in
// microsteps from where it stood at power-on (SAP 1 and reference searches do not move them);
// the motion core reports each closing and opening at its exact instant. Both kinds may be mixed:
// an input is closed while either closes it.
// Times are absolute simulated instants (durations as in duration.hpp); events at the same
// instant apply in file order. Every bad line is reported, like the assembler does, as
// FILE:LINE:COL: error: ... with the line and a caret (and a did-you-mean for a misspelt
// input kind), up to ScenarioOptions::error_limit errors.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "tmcl/diag_text.hpp"
#include "tmcl/vm.hpp"

namespace tmcl {

// The first words of a scenario line; a test file hands its lines that start with one of them to
// parse_scenario (one reader for both).
inline constexpr std::string_view kScenarioLineWords[] = {"at", "switch", "hardstop", "load"};
inline bool is_scenario_line(std::string_view first_word) {
  for (auto w : kScenarioLineWords)
    if (w == first_word) return true;
  return false;
}

struct ScenarioOptions {
  int motors = 256;        // a motor event for motor >= motors is an error naming `module`
  std::string module;      // e.g. "usb-2-sd"
  // Non-empty: the motion core (its name) models no encoder on `module`
  // (MotionCore::models_encoder), and a `slip` line is an error naming it.
  std::string no_encoder;
  int error_limit = kDefaultErrorLimit;  // 0 = report every error
  // The module's profile: `input N` and `analog N` must name a digital input of bank 0 and an
  // input of bank 1 it lists, with a value in the port's range (errata E53). Null: ports 0..7.
  const Profile* profile = nullptr;
  // The lines describe the machine at power-on, the carriage at position 0: a hard stop beyond it
  // is an error. False: placed mid-run, wherever the carriage is (the debugger's `set var`).
  bool from_start = true;
};

// Parses every line; returns false when any is bad, with `diags` holding every error in line order.
bool parse_scenario(const std::string& text, const std::string& file, std::vector<InputEvent>& out,
                    std::vector<FileDiag>& diags, const ScenarioOptions& options = {});
// The same, with the errors rendered (capped at options.error_limit) into `error`.
bool parse_scenario(const std::string& text, const std::string& file, std::vector<InputEvent>& out,
                    std::string& error, const ScenarioOptions& options = {});

}  // namespace tmcl
