// The readable view of objects and libraries (tmclasm --dump-object), stable for golden tests.
// It lives apart from the object format (object.cpp) because it shows each instruction
// disassembled: the format reader stays below the disassembler, and nothing includes in a circle.
#include <cstdio>

#include "tmcl/asm/disasm.hpp"
#include "tmcl/asm/object.hpp"
#include "tmcl/codec.hpp"

namespace tmcl {
namespace {

// A relocated field's word in the dump ("reloc motor = ..."), shorter than codec's field_name.
const char* field_word(Field f) {
  switch (f) {
    case Field::Type: return "type";
    case Field::Motor: return "motor";
    case Field::Value: return "value";
  }
  return "?";
}

}  // namespace

std::string dump_object(const ObjectFile& obj) {
  std::string out;
  char buf[160];
  out += "object format " + std::to_string(kObjectVersion) + "\ntarget " + obj.target + "\nflags";
  out += obj.flags & kObjNoAppendStop ? " no-append-stop\n" : " none\n";
  auto where = [&](std::uint32_t file, std::uint32_t line) {
    if (file == kNoIndex) return std::string("-");
    return obj.files[file] + ":" + std::to_string(line);
  };
  out += "files " + std::to_string(obj.files.size()) + "\n";
  for (std::size_t i = 0; i < obj.files.size(); ++i) out += "  " + std::to_string(i) + "  " + obj.files[i] + "\n";
  out += "symbols " + std::to_string(obj.symbols.size()) + "\n";
  static const char* kinds[] = {"label", "const"};
  static const char* bindings[] = {"local", "export", "import"};
  for (std::size_t i = 0; i < obj.symbols.size(); ++i) {
    const ObjSymbol& s = obj.symbols[i];
    std::string value;
    if (s.binding == ObjBinding::Import) value = "?";
    else if (s.term == ObjTerm::Base) value = "base+" + std::to_string(s.value);
    else if (s.term == ObjTerm::Symbol)
      value = obj.symbols[s.term_symbol].name + (s.value < 0 ? "" : "+") + std::to_string(s.value);
    else value = std::to_string(s.value);
    std::snprintf(buf, sizeof buf, "  %-3zu %-6s %-6s ", i, s.binding == ObjBinding::Import ? "-" : kinds[static_cast<int>(s.kind)],
                  bindings[static_cast<int>(s.binding)]);
    out += buf + s.name + "  " + value + "  " + where(s.file, s.line) + "\n";
  }
  out += "code " + std::to_string(obj.code.size()) + "\n";
  std::size_t rel = 0;
  for (std::size_t i = 0; i < obj.code.size(); ++i) {
    const Instruction& ins = obj.code[i];
    auto b = encode7(ins);
    std::snprintf(buf, sizeof buf, "  %04zu  %02X %02X %02X %02X %02X %02X %02X  ", i, b[0], b[1], b[2], b[3], b[4], b[5],
                  b[6]);
    out += buf;
    out += where(obj.lines[i].file, obj.lines[i].line);
    out += "  " + format_instruction(ins);
    if (obj.code_flags[i] & kInsRaw) out += "  (raw)";
    out += "\n";
    for (; rel < obj.relocs.size() && obj.relocs[rel].index == i; ++rel) {
      const ObjReloc& x = obj.relocs[rel];
      std::string target = x.term == ObjTerm::Base ? "base" : obj.symbols[x.symbol].name;
      out += "        reloc " + std::string(field_word(x.field)) + " = " + target + (x.addend < 0 ? "" : "+") +
             std::to_string(x.addend) + "\n";
    }
  }
  return out;
}

std::string dump_library(const Library& lib) {
  std::string out = "library format " + std::to_string(kObjectVersion) + ", " + std::to_string(lib.members.size()) +
                    (lib.members.size() == 1 ? " member\n" : " members\n");
  for (const auto& m : lib.members) {
    out += "\n=== member " + m.name + "\n";
    out += dump_object(m.object);
  }
  return out;
}

}  // namespace tmcl
