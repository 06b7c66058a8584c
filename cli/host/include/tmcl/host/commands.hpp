// What tmclctl's words mean, kept out of the tool so that tests and embedders reach it:
// parameters by number or by the profile's name, and the decoded forms of the status replies
// (135, 136). Instructions from source syntax: console.hpp.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tmcl/isa.hpp"
#include "tmcl/profile.hpp"

namespace tmcl::host {

// A parameter: axis (GAP/SAP/STAP), global (GGP/SGP/STGP) or I/O (GIO/SIO).
struct ParamRef {
  enum Kind : std::uint8_t { Axis, Global, Io } kind = Axis;
  int number = 0;
  int index = 0;  // motor (axis), bank (global, I/O)
  const ParamInfo* info = nullptr;  // from the profile, when it has the parameter
  std::string label() const;        // "axis parameter 1 (Actual position), motor 0"
};

// Reads a parameter from words[at..], advancing `at`:
//   ap N [MOTOR] | gp N [BANK] | io N [BANK] | ap:N[:MOTOR] | gp:N[:BANK] | io:N[:BANK]
//   | NAME [MOTOR]   (an axis, bank-0 or bank-3 global parameter of the profile, any case, e.g.
//                     'actual position', 'timer 0 period'; an unknown name gets a did-you-mean)
// With `single_word`, only the one-word forms (for monitor, which takes a list). `keep` words
// after the parameter belong to the command (set: its value): an optional motor or bank is
// taken only from words beyond them.
bool parse_param(const std::vector<std::string>& words, std::size_t& at, const Profile& profile, bool single_word,
                 ParamRef& out, std::string& error, std::size_t keep = 0);

enum class ParamAction : std::uint8_t { Get, Set, Store };
// The instruction for an action on `p` (Set with `value`); false with `error` when the module's
// profile says the parameter cannot do it (not writable, not stored in EEPROM, I/O store, a
// motor the module lacks, a user variable beyond bank 2 or without an EEPROM copy).
bool param_instruction(const ParamRef& p, ParamAction action, std::int32_t value, const Profile& profile, Instruction& out,
                       std::string& error);

// 135 type 0/1 value: mode byte 3, wait flag byte 2, pointer or pc bytes 1-0.
std::string mode_name(std::uint32_t mode);  // "stopped", "running", "step", "reset", "download"

}  // namespace tmcl::host
