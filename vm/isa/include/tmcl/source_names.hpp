// The names a program's source gave its addresses and operands, so that an instruction can be
// shown as the source wrote it: `JC LT, Loop`, `CSUB Home`, `SAP 4, 0, MaxSpeed` rather than
// `JC LT, 3`, `CSUB 12`, `SAP 4, 0, 51200`. tmclrun --trace and the debugger's disassemble and
// x/i show instructions so. The assembler fills them from a program's sources (tmcl::source_names
// and tmcl::named_operands, asm/include/tmcl/asm/names.hpp); a symbols file gives labels only.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "tmcl/codec.hpp"

namespace tmcl {

struct SourceNames {
  // A label of each labelled address (the first defined there).
  std::unordered_map<std::int64_t, std::string> labels;
  // Per address, per field (indexed by Field: type, motor, value), the operand as the source
  // wrote it where that was a name or an expression over names; empty where it was a number or
  // a keyword, and for addresses past the end of the vector.
  std::vector<std::array<std::string, 3>> operands;
};

// The instruction at `address` as source text: an operand the source named as written, a
// program address by its label, a keyword by name, any other operand as a number. Without
// `names` (or with none for that address), exactly tmcl's plain form of the instruction table.
// Unknown opcodes and control commands: "?? OP, TYPE, MOTOR, VALUE".
std::string named_instruction_text(const Instruction& ins, std::int64_t address, const SourceNames* names);

}  // namespace tmcl
