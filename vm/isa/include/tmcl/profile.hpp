// Module profiles: what one TMCL module offers (commands, parameters, banks, memory, motion), as
// data. The assembler checks programs against a profile; the VM takes its limits and defaults
// from it. Profiles are text files (docs/profiles.md): the bundled ones in vm/isa/profiles/ are
// compiled into the tools, a user's own are read at run time (profile_file.hpp, targets.hpp).
// Nothing else in the code branches on a module. `Profile` is a view: its spans and strings point
// into the storage of the file it was read from, which lives as long as the program.
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

// "RWE": the letters of Access bits in the manuals' order R, W, E, A (empty for none).
std::string access_letters(std::uint8_t access);

// The facts of a parameter line a profile may mark `unverified` (no source confirms them).
enum Fact : std::uint8_t {
  kFactName = 1,
  kFactRange = 2,
  kFactAccess = 4,
  kFactDefault = 8,
  kFactUnit = 16,
  kFactExists = 32,  // that the module has the parameter at all
};

// One item of a parameter's value set (`values=` in a profile): the values lo … hi, or (flag) a
// number that may be added to any of them (+128: "adding 128 inverts the home switch").
struct ValueItem {
  std::int64_t lo, hi;
  bool flag = false;
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
  std::string_view source = {};  // where the facts come from, as the file says ("M:5.1")
  std::uint8_t unverified = 0;   // Fact bits no source confirms
  // The values the manual lists, where a range says too little (193: 1..8, +64, +128); empty: every
  // value of the range. A value must be in the range and, when there is a set, in the set.
  std::span<const ValueItem> values = {};
  // Why the virtual module does not do what the module does with this parameter (the profile's
  // not-simulated="REASON"); empty where it does. A program that writes or reads it gets a note
  // once per run (a warning under --strict); the conformance table's row says "not simulated".
  std::string_view not_simulated = {};
};

// Whether a parameter takes `value`: within [min, max] read as signed, or (a value that fits 32
// bits) read as unsigned, since a 32-bit field holds either and either may be the meant one. The
// one range rule of the assembler's checks, the VM's writes and the debugger's `set`.
bool accepts(const ParamInfo& p, std::int64_t value);
// The range as diagnostics write it: "0 to 16777215 pps"; a value set as "1 to 8, optionally +64, +128".
std::string range_text(const ParamInfo& p);
// "axis parameter 4 (Maximum positioning speed)"; `kind` is "axis parameter" or "global parameter".
std::string param_text(std::string_view kind, int number, const ParamInfo* p);

struct InterruptVector {
  std::uint8_t number;
  std::string_view name;  // e.g. "TI_TIMER0", the Interrupts.inc symbol
  std::string_view meaning;
};

// An I/O port of the module, as its manual's GIO/SIO tables list it (`port` in a profile). GIO
// reads bank 0 (digital inputs), bank 1 (analog inputs) and bank 2 (the outputs' states); SIO
// writes bank 2 (outputs) and, on some modules, settings in bank 0 (pull-up resistors, an input
// range). A `bits` port reads or writes every digital port of its bank at once as a bit vector
// (GIO 255, 0; SIO 255, 2).
enum class PortKind : std::uint8_t { Digital, Analog, Bits };
// Port numbers a profile may list: 0 … kPortCount-1 (no manual lists more), and 255 for a bits port.
inline constexpr int kPortCount = 16;
struct IoPort {
  std::uint8_t bank;
  std::uint8_t number;
  std::string_view name;  // the manual's ("IN0", "Supply voltage")
  bool output;            // SIO writes it (bank 2: GIO reads it back); else GIO reads it
  PortKind kind;
  std::int64_t min, max;  // digital: 0..1; a bits port: 0 .. 2^digital ports - 1
  std::int32_t default_value;  // what an input reads until a scenario sets it (supply voltage)
  std::string_view unit;
  std::string_view source = {};
  bool unverified = false;
};
// "GIO 8, 1 (Supply voltage)"
std::string port_text(const IoPort& p);

// A named constant of the module's motion core (clock frequency, unit conversions), for the core
// to read with Profile::motion_constant.
struct MotionConstant {
  std::string_view name;
  std::int64_t value;
};

// Where a module keeps its stored program: in EEPROM it survives a power cycle, in RAM it does not.
enum class ProgramStore : std::uint8_t { Unknown, Ram, Eeprom };

struct Profile {
  std::string_view name;      // -t NAME
  std::string_view title;     // "USB-2-SD (firmware 1.14)"
  std::bitset<256> commands;  // opcodes the module executes, control commands included
  bool any_parameter;         // generic: every parameter number is accepted without access checks;
                              // a value is range-checked where the tables list the parameter
  std::span<const ParamInfo> axis_params;  // sorted by number, as bank0 and bank3
  std::span<const ParamInfo> bank0;  // global parameters, bank 0
  std::span<const ParamInfo> bank3;  // interrupt configuration, bank 3
  int user_vars;              // bank 2 size
  int eeprom_user_vars;       // how many of them STGP/RSGP can back (from 0)
  int coords;                 // coordinates per motor (0..coords-1)
  std::span<const InterruptVector> vectors;
  std::span<const IoPort> ports;  // sorted by bank, number, then inputs first
  bool any_port = false;          // `ports any` (generic): every port 0..255 of banks 0..2, unchecked
  int program_memory;         // in instructions; 0 = unlimited
  int motors;
  std::string_view default_motion;  // name of the default motion core
  std::string_view firmware;        // 136 type 0 reply text, 8 characters, e.g. "0015V114"

  bool standalone = true;  // runs standalone programs (has program memory at all)
  ProgramStore program_store = ProgramStore::Unknown;  // whether the program survives a power cycle
  std::string_view fallback_motion;  // the core to use while default_motion is not built in
  std::string_view include_file;     // the module's bundled include file ("USB-2-SD.inc"), if any
  std::span<const MotionConstant> motion_constants;
  std::span<const std::string_view> aliases;     // other -t names ("pd60-1260")
  std::span<const std::string_view> unverified;  // every fact no source confirms, one phrase each
  std::string_view origin;  // "bundled", or the file it was read from
  std::string_view text;    // the profile file as read (--show-target)

  bool has_command(std::uint8_t op) const { return commands.test(op); }
  const ParamInfo* axis_param(int number) const;
  // Bank 0 or 3 parameter; nullptr for other banks or unknown numbers.
  const ParamInfo* global_param(int bank, int number) const;
  const InterruptVector* vector(int number) const;
  // The port GIO (read) or SIO (write) reaches at `number` of `bank`: for a read an input, or on
  // bank 2 an output read back; nullptr when the module has none there.
  const IoPort* read_port(int bank, int number) const;
  const IoPort* write_port(int bank, int number) const;
  // The port numbers GIO (read) or SIO (write) reaches in `bank`, as "0, 1, 2, 255" ("none"):
  // what the VM's no-such-port warning and the assembler's port warning list.
  std::string port_numbers(int bank, bool write) const;
  // Whether digital input n (GIO n, 0) exists: a listed digital input, or any under `ports any`.
  bool digital_input(int n) const;
  // The highest port number of `bank` the profile lists (inputs of 0 and 1, outputs of 2), -1: none.
  int last_port(int bank) const;
  // The motion constant NAME, or `otherwise` when the profile does not give it.
  std::int64_t motion_constant(std::string_view constant, std::int64_t otherwise) const;
};

// A profile file's extension: NAME.profile, bundled or on the search path.
inline constexpr std::string_view kProfileExtension = ".profile";

// All bundled profiles, generic first, then by name.
std::span<const Profile* const> all_profiles();
// A bundled profile by -t name or alias, or nullptr. A user's profiles are found with
// resolve_target (targets.hpp).
const Profile* find_profile(std::string_view name);
const Profile& generic_profile();

}  // namespace tmcl
