// ProgramInfo (tmcl/expr.hpp): a program's source places, labels and constants, looked up by
// address or by name for the debugger's and the test runner's messages and expressions.
#include <cctype>

#include "tmcl/expr.hpp"

namespace tmcl {

std::string ProgramInfo::place(std::int32_t address) const {
  if (address < 0 || static_cast<std::size_t>(address) >= lines.size()) return "";
  const Line& l = lines[static_cast<std::size_t>(address)];
  if (l.file < 0 || static_cast<std::size_t>(l.file) >= files.size()) return "";
  return files[static_cast<std::size_t>(l.file)].name + ":" + std::to_string(l.line);
}

std::string ProgramInfo::function_of(std::int32_t address) const {
  const std::pair<std::string, std::int64_t>* best = nullptr;
  for (const auto& l : labels)
    if (l.second <= address && (!best || l.second > best->second)) best = &l;
  if (!best) return "";
  return best->second == address ? best->first : best->first + "+" + std::to_string(address - best->second);
}

std::optional<std::int64_t> ProgramInfo::symbol(const std::string& name) const {
  auto same = [&](const std::string& s) {
    if (s.size() != name.size()) return false;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(s[i])) != std::tolower(static_cast<unsigned char>(name[i]))) return false;
    return true;
  };
  for (const auto& l : labels)
    if (same(l.first)) return l.second;
  for (const auto& c : constants)
    if (same(c.first)) return c.second;
  return std::nullopt;
}

const std::string* ProgramInfo::source_text(std::int32_t address) const {
  if (address < 0 || static_cast<std::size_t>(address) >= lines.size()) return nullptr;
  const Line& l = lines[static_cast<std::size_t>(address)];
  if (l.file < 0 || static_cast<std::size_t>(l.file) >= files.size()) return nullptr;
  const auto& text = files[static_cast<std::size_t>(l.file)].text;
  if (l.line < 1 || static_cast<std::size_t>(l.line) > text.size()) return nullptr;
  return &text[static_cast<std::size_t>(l.line - 1)];
}

}  // namespace tmcl
