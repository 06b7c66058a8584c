// The disassembler: a TMCL-IDE .bin, datagrams or an object back to .tmc source that
// reassembles to the identical bytes (docs/tmclasm.md, "Disassembly"). Symbolic keywords, a
// label at every jump, call and vector target, the address of every instruction in a comment;
// `.raw` for any record the mnemonic form cannot express exactly (or only with a warning).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tmcl/asm/object.hpp"
#include "tmcl/isa.hpp"

namespace tmcl {

// One instruction as source without labels ("MVP ABS, 0, 1000", "JA 12", ".raw 99, 0, 0, 0").
std::string format_instruction(const Instruction& ins);

// Label names for a .bin, from a symbols file (tmclasm -f symbols).
struct LabelNames {
  std::vector<std::pair<std::string, std::int64_t>> labels;  // name, address; in file order
};
// Parses the symbols format of docs/tmclasm.md; false with `error` ("line 3: ...") when it is not one.
bool parse_symbols(const std::string& text, LabelNames& out, std::string& error);

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
  const LabelNames* names = nullptr; // --symbols
  bool warnings_are_errors = false;
};

// Disassembles the file `name` holding `bytes`.
DisasmResult disassemble(const std::string& name, const std::string& bytes, const DisasmOptions& options);

// The parts, for tests and embedders: a program at address 0, and an object.
std::string disassemble_program(const std::vector<Instruction>& program, const LabelNames* names,
                                const std::vector<std::string>& header, const std::vector<std::string>& notes);
std::string disassemble_object(const ObjectFile& obj, const std::vector<std::string>& header);

}  // namespace tmcl
