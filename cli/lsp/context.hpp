// Private to tmcl_lsp: how the requests read a line of the assembler's tokens (tokenize) — which
// instruction a token belongs to and which operand it is — and how they compare names. Shared by
// hover and completion (features.cpp), semantic tokens (tokens.cpp) and inlay hints (hints.cpp),
// so that every request reads a statement the same way.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/asm/format.hpp"
#include "tmcl/isa.hpp"

namespace tmcl::lsp {

// The kind of an assembler token; every file of the server reads tokens.
using Kind = SourceToken::Kind;

// The statement a token is in: its mnemonic (nullptr when the line holds no instruction) and which
// operand (0-based, -1 for the mnemonic itself) the token belongs to.
struct Context {
  const OpInfo* op = nullptr;
  const SourceToken* mnemonic = nullptr;  // the token naming op
  int operand = -1;
  std::vector<const SourceToken*> operands_first;  // first token of each operand of the line
  // What the instruction table says of the token's operand; nullptr outside the operands.
  const OperandSpec* spec() const {
    return op && operand >= 0 && static_cast<std::size_t>(operand) < op->operands.size() ? &op->operands[static_cast<std::size_t>(operand)] : nullptr;
  }
};

// The context of toks[index]; toks is a whole document or one line, lines ended by Newline tokens.
Context context_at(const std::vector<SourceToken>& toks, std::size_t index);

// The bank a global-parameter instruction names: its Bank operand when that is a bare number,
// else 0 (the manuals' default bank).
int bank_of(const Context& c);

// Names are case-insensitive (docs/language.md, "Names").
std::string lower(std::string_view s);
bool same_name(std::string_view a, std::string_view b);

}  // namespace tmcl::lsp
