// The TMCL instruction set as data: opcodes, operand shapes and keyword sets, expanded from
// opcodes.def and keywords.def. Assembler, disassembler, VM and docs all read these tables.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "tmcl/codec.hpp"  // Instruction, Field and their byte forms

namespace tmcl {

enum class Op : std::uint8_t {
#define TMCL_OP(code, id, mn, meaning, ...) id = code,
#define TMCL_CTL(code, id, meaning) id = code,
#include "tmcl/opcodes.def"
#undef TMCL_OP
#undef TMCL_CTL
};

// What an operand means; drives profile checks, listings and documentation.
enum class Role : std::uint8_t {
  Data,         // any 32-bit value
  Motor,        // motor (axis) number
  Bank,         // global parameter bank
  AxisParam,    // axis parameter number
  GlobalParam,  // global parameter number (meaning depends on the bank)
  Var,          // user variable number (bank 2)
  Coord,        // coordinate number
  Interrupt,    // interrupt vector number
  Port,         // I/O port number
  Velocity,     // velocity in pps
  Position,     // position in microsteps (or coordinate number with COORD)
  Ticks,        // 10 ms ticks (WAIT)
  Address,      // program address (label)
  Keyword,      // from a keyword set
};

enum class KwSet : std::uint8_t { None, Move, CalcA, CalcX, CalcV, CalcVV, Cond, Wait, Cle, Rfs };

// Every keyword's value by name, for the code that executes them: `case kw::Move::REL:`, not
// `case 1:`. Generated from keywords.def, as the assembler's table is.
namespace kw {
#define KEYWORD(set, name, value) \
  namespace set {                 \
  inline constexpr int name = value; \
  }
#include "tmcl/keywords.def"
#undef KEYWORD
}  // namespace kw

struct OperandSpec {
  Field field;
  Role role;
  KwSet keywords = KwSet::None;
};

struct OpInfo {
  std::uint8_t code;
  std::string_view id;        // enum name
  std::string_view mnemonic;  // empty for direct-mode control commands
  std::string_view meaning;
  std::span<const OperandSpec> operands;
  bool control;  // direct-mode only (128..138, 255)
};

struct Keyword {
  KwSet set;
  std::string_view name;
  std::uint8_t value;
};

// All opcodes in table order.
std::span<const OpInfo> all_ops();
// The opcode with this number, or nullptr when the number is not a TMCL opcode.
const OpInfo* op_info(std::uint8_t code);
// Case-insensitive mnemonic lookup; nullptr when unknown.
const OpInfo* op_by_mnemonic(std::string_view mnemonic);

std::span<const Keyword> all_keywords();
// Case-insensitive lookup of a keyword in one set.
std::optional<std::uint8_t> keyword_value(KwSet set, std::string_view name);
// Whether `name` is a keyword of any set (case-insensitive).
bool is_keyword(std::string_view name);
// The keyword of `set` with this value (for the disassembler), if any.
std::optional<std::string_view> keyword_name(KwSet set, std::uint8_t value);
std::string_view kwset_name(KwSet set);
std::string_view role_name(Role role);

}  // namespace tmcl
