// Fuzzes the symbols file reader (asm/symbols.cpp): any bytes are either refused with a line
// number inside the text or read into a line table whose runs are in address order, do not
// overlap, name declared files, and agree with LineTable::at.
#include <cstdint>
#include <string>

#include "tmcl/asm/symbols.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  tmcl::LabelNames names;
  int line = -1;
  std::string error;
  if (!tmcl::parse_symbols(text, names, line, error)) {
    if (error.empty() || line < 0 || static_cast<std::size_t>(line) > size + 1) __builtin_trap();
    return 0;
  }
  std::int64_t end = 0;
  for (const auto& r : names.lines.runs) {
    if (r.address < end || r.count < 1 || r.line < 1 || r.file < 0 ||
        static_cast<std::size_t>(r.file) >= names.lines.files.size())
      __builtin_trap();
    auto first = names.lines.at(r.address), last = names.lines.at(r.address + r.count - 1);
    if (first.first != r.file || first.second != r.line || last.second != r.line + r.count - 1) __builtin_trap();
    end = r.address + r.count;
  }
  if (names.lines.at(end).first != -1) __builtin_trap();
  return 0;
}
