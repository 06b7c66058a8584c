// Compares two assembler results field by field (what tools print from them): used to check
// that the fast path and the full assembler agree. Empty when equal, else the first difference.
#pragma once

#include <string>

#include "tmcl/asm/assembler.hpp"

namespace tmcl_test {

inline std::string loc_text(const tmcl::SourceLoc& l) {
  return std::to_string(l.file) + ":" + std::to_string(l.line) + ":" + std::to_string(l.col) + "+" +
         std::to_string(l.len);
}

inline std::string result_difference(const tmcl::AsmResult& a, const tmcl::AsmResult& b) {
  if (a.ok() != b.ok()) return "ok differs";
  if (a.diags.all().size() != b.diags.all().size()) return "diagnostic count differs";
  if (a.diags.render(a.sources) != b.diags.render(b.sources)) return "diagnostics differ";
  if (a.program.size() != b.program.size()) return "program size differs";
  for (std::size_t i = 0; i < a.program.size(); ++i)
    if (!(a.program[i] == b.program[i])) return "instruction " + std::to_string(i) + " differs";
  if (a.lines.size() != b.lines.size()) return "line count differs";
  for (std::size_t i = 0; i < a.lines.size(); ++i)
    if (a.lines[i].file != b.lines[i].file || a.lines[i].line != b.lines[i].line)
      return "line of instruction " + std::to_string(i) + " differs";
  if (a.symbols.size() != b.symbols.size()) return "symbol count differs";
  for (std::size_t i = 0; i < a.symbols.size(); ++i) {
    const auto &x = a.symbols[i], &y = b.symbols[i];
    if (x.name != y.name || x.kind != y.kind || x.value != y.value || x.exported != y.exported ||
        loc_text(x.defined_at) != loc_text(y.defined_at))
      return "symbol " + x.name + " differs from " + y.name;
  }
  if (a.inputs.size() != b.inputs.size()) return "input count differs";
  for (std::size_t i = 0; i < a.inputs.size(); ++i)
    if (a.inputs[i].name != b.inputs[i].name || a.inputs[i].first != b.inputs[i].first ||
        a.inputs[i].count != b.inputs[i].count || a.inputs[i].reason != b.inputs[i].reason)
      return "input " + a.inputs[i].name + " differs";
  if (a.profile != b.profile) return "profile differs";
  if (a.appended_stop != b.appended_stop) return "appended STOP differs";
  if (a.sources.files.size() != b.sources.files.size()) return "source count differs";
  for (std::size_t i = 0; i < a.sources.files.size(); ++i) {
    const auto &x = a.sources.files[i], &y = b.sources.files[i];
    if (x.name != y.name || x.path != y.path || x.text != y.text || x.includer != y.includer ||
        x.include_line != y.include_line || x.line_starts != y.line_starts)
      return "source " + x.name + " differs";
  }
  return "";
}

}  // namespace tmcl_test
