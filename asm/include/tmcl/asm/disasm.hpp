// The disassembler: a TMCL-IDE .bin, datagrams or an object back to .tmc source that
// reassembles to the identical bytes (docs/tmclasm.md, "Disassembly"). Symbolic keywords, a
// label at every jump, call and vector target, the address of every instruction in a comment;
// `.raw` for any record the mnemonic form cannot express exactly (or only with a warning).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tmcl/asm/object.hpp"
#include "tmcl/asm/symbols.hpp"
#include "tmcl/isa.hpp"

namespace tmcl {

// One instruction as source without labels ("MVP ABS, 0, 1000", "JA 12", ".raw 99, 0, 0, 0").
std::string format_instruction(const Instruction& ins);
// The same with some operands written as the given text instead of a number ("JC LT, loop",
// "COMP Limit"): a name in a keyword's place is parenthesised, as in an object's listing.
std::string format_instruction(const Instruction& ins, const std::map<Field, std::string>& names);

enum class ImageKind { Auto, Bin, Datagrams, Object, Library };

struct DisasmMessage {
  bool error;
  std::string text;  // without the file name
};

struct DisasmResult {
  std::string source;
  std::vector<DisasmMessage> messages;
  bool ok() const {
    for (const auto& m : messages)
      if (m.error) return false;
    return true;
  }
};

struct DisasmOptions {
  ImageKind kind = ImageKind::Auto;  // Auto: object or library by magic, datagrams by .dgm, else .bin
  const LabelNames* names = nullptr; // --symbols: label names; a line table adds "file:line" comments
  bool warnings_are_errors = false;
};

// Disassembles the file `name` holding `bytes`.
DisasmResult disassemble(const std::string& name, const std::string& bytes, const DisasmOptions& options);

// The parts, for tests and embedders: a program at address 0, and an object.
std::string disassemble_program(const std::vector<Instruction>& program, const LabelNames* names,
                                const std::vector<std::string>& header, const std::vector<std::string>& notes);
std::string disassemble_object(const ObjectFile& obj, const std::vector<std::string>& header);

}  // namespace tmcl
