// Fuzzes the profile file reader (vm/isa/profile_file.cpp) on arbitrary text. Checks: no crash,
// no hang; a file that is refused says why, in the FILE:LINE form; a file that is accepted gives
// a consistent profile (tables sorted, defaults in range) whose draft (format_profile) reads back.
#include <cstdint>
#include <string>
#include <vector>

#include "tmcl/profile_file.hpp"

namespace {
bool consistent(std::span<const tmcl::ParamInfo> table) {
  for (std::size_t i = 0; i < table.size(); ++i) {
    if (i > 0 && table[i - 1].number >= table[i].number) return false;
    if (table[i].min > table[i].max) return false;
  }
  return true;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<tmcl::FileDiag> diags;
  auto lookup = [](std::string_view name, std::string&) { return tmcl::find_profile(name); };
  auto store = tmcl::parse_profile(text, "f.profile", "f.profile", diags, lookup);
  if (!store) {
    if (diags.empty()) __builtin_trap();  // a refused file must say why
    if (tmcl::render_file_diags(diags, 20).rfind("f.profile:", 0) != 0) __builtin_trap();
    return 0;
  }
  const tmcl::Profile& p = store->profile;
  if (!consistent(p.axis_params) || !consistent(p.bank0) || !consistent(p.bank3)) __builtin_trap();
  if (p.motors < 1 || p.eeprom_user_vars > p.user_vars) __builtin_trap();
  std::vector<tmcl::FileDiag> again;
  if (!tmcl::parse_profile(tmcl::format_profile(p), "draft.profile", "draft", again, lookup)) __builtin_trap();
  return 0;
}
