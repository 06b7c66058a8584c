// Module profiles: what one TMCL module offers (commands, parameters, banks, memory), as data.
// The assembler checks programs against a profile; the VM takes its limits and defaults from it.
// There is one table per module in vm/profiles/; nothing else in the code branches on a module.
#pragma once

#include <bitset>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tmcl {

// Access letters as the manuals use them.
enum Access : std::uint8_t {
  kRead = 1,       // R: GAP/GGP
  kWrite = 2,      // W: SAP/SGP/AAP/AGP
  kEeprom = 4,     // E: STAP/RSAP, STGP/RSGP
  kAutoStore = 8,  // A: SGP stores it in EEPROM at once
};

struct ParamInfo {
  std::uint16_t number;
  std::string_view name;  // the manual's name
  std::int64_t min;
  std::int64_t max;
  std::uint8_t access;    // Access bits
  std::int32_t default_value;
  // The unit of the manual's "Range [Units]" column ("pps", "μsteps"); empty where it gives none.
  std::string_view unit;
};

// Whether a parameter takes `value`: within [min, max] read as signed, or (a value that fits 32
// bits) read as unsigned, since a 32-bit field holds either and either may be the meant one. The
// one range rule of the assembler's checks, the VM's writes and the debugger's `set`.
bool accepts(const ParamInfo& p, std::int64_t value);
// The range as diagnostics write it: "0 to 16777215 pps".
std::string range_text(const ParamInfo& p);
// "axis parameter 4 (Maximum positioning speed)"; `kind` is "axis parameter" or "global parameter".
std::string param_text(std::string_view kind, int number, const ParamInfo* p);

struct InterruptVector {
  std::uint8_t number;
  std::string_view name;  // e.g. "TI_TIMER0", the Interrupts.inc symbol
  std::string_view meaning;
};

struct Profile {
  std::string_view name;      // -t NAME
  std::string_view title;     // "USB-2-SD (firmware 1.14)"
  std::bitset<256> commands;  // opcodes the module executes, control commands included
  bool any_parameter;         // generic: every parameter number is accepted without access checks;
                              // a value is range-checked where the tables list the parameter
  std::span<const ParamInfo> axis_params;
  std::span<const ParamInfo> bank0;  // global parameters, bank 0
  std::span<const ParamInfo> bank3;  // interrupt configuration, bank 3
  int user_vars;              // bank 2 size
  int eeprom_user_vars;       // how many of them STGP/RSGP can back (from 0)
  int coords;                 // coordinates per motor (0..coords-1)
  std::span<const InterruptVector> vectors;
  int program_memory;         // in instructions; 0 = unlimited
  int motors;
  std::string_view default_motion;  // name of the default motion core
  std::string_view firmware;        // 136 type 0 reply text, 8 characters, e.g. "0015V114"

  bool has_command(std::uint8_t op) const { return commands.test(op); }
  const ParamInfo* axis_param(int number) const;
  // Bank 0 or 3 parameter; nullptr for other banks or unknown numbers.
  const ParamInfo* global_param(int bank, int number) const;
  const InterruptVector* vector(int number) const;
};

// All built-in profiles, generic first.
std::span<const Profile* const> all_profiles();
// Their -t names, in the same order (the tools' completion and messages).
std::vector<std::string> profile_names();
// Profile by -t name, or nullptr.
const Profile* find_profile(std::string_view name);
const Profile& generic_profile();

}  // namespace tmcl
