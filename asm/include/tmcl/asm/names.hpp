// The names a program's source gave its operands and addresses (tmcl/source_names.hpp), read
// back from the sources after assembly: for tmclrun --trace and the debugger's disassembly, which
// show `JC LT, Loop` and `SAP 4, 0, MaxSpeed` where the source said so.
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "tmcl/source_names.hpp"

namespace tmcl {

struct AsmResult;

// The operands of the instruction `ins` on the source line `line` (labels before it, comments
// after it allowed), per field (indexed by Field), as written where the source wrote a name or
// an expression over names; empty where it wrote a number, an expression of numbers or a keyword
// of the operand's set, and all empty when the line does not hold that instruction's mnemonic.
std::array<std::string, 3> named_operands(std::string_view line, const Instruction& ins);

// The names of an assembled program: every label (AsmResult::symbols, so AsmOptions::symbols
// must be set) and the named operands of every instruction whose source line is known.
SourceNames source_names(const AsmResult& result);

}  // namespace tmcl
