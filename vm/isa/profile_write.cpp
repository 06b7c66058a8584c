// format_profile: a profile written in the file format (profile_file.hpp), for the drafts that
// `tmclctl probe` writes and anything else that makes a profile from data rather than from a
// file. Sources are not written (a draft has none); facts the profile marks unverified are
// marked so again.
#include <algorithm>

#include "tmcl/profile_file.hpp"

namespace tmcl {
namespace {

std::string quoted(std::string_view text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? '\'' : (c == '\n' || c == '\r') ? ' ' : c;
  return out + "\"";
}

// Attribute value: bare when it is one word, else quoted.
std::string attr_value(std::string_view text) {
  const bool bare = !text.empty() && text.find_first_of(" \t\"#=") == std::string_view::npos;
  return bare ? std::string(text) : quoted(text);
}

std::string facts(std::uint8_t bits) {
  if (bits == 0) return "";
  if (bits == 0xFF) return " unverified";
  static constexpr std::pair<Fact, std::string_view> kFacts[] = {
      {kFactExists, "exists"}, {kFactName, "name"}, {kFactRange, "range"},
      {kFactAccess, "access"}, {kFactDefault, "default"}, {kFactUnit, "unit"}};
  std::string out = " unverified=";
  const char* sep = "";
  for (const auto& [bit, word] : kFacts)
    if (bits & bit) out += sep + std::string(word), sep = ",";
  return out;
}

std::string param(const ParamInfo& q) {
  std::string line = std::to_string(q.number) + " " + quoted(q.name) + " " + std::to_string(q.min) + ".." +
                     std::to_string(q.max) + " " + access_letters(q.access);
  std::int64_t d = q.default_value;
  if (d < q.min) d = static_cast<std::uint32_t>(q.default_value);  // an unsigned range's high half
  line += " default=" + std::to_string(d);
  if (!q.unit.empty()) line += " unit=" + attr_value(q.unit);
  if (!q.not_simulated.empty()) line += " not-simulated=" + quoted(q.not_simulated);
  return line + facts(q.unverified);
}

}  // namespace

std::string format_profile(const Profile& p, std::string_view note) {
  auto unverified = [&](std::string_view key) {
    return std::find(p.unverified.begin(), p.unverified.end(), key) != p.unverified.end() ? " unverified" : "";
  };
  std::string out;
  for (std::size_t pos = 0; pos < note.size();) {
    std::size_t end = std::min(note.find('\n', pos), note.size());
    out += "# " + std::string(note.substr(pos, end - pos)) + "\n";
    pos = end + 1;
  }
  out += "tmcl-profile 1\n";
  out += "name " + std::string(p.name) + "\n";
  if (!p.aliases.empty()) {
    out += "alias";
    for (auto a : p.aliases) out += " " + std::string(a);
    out += "\n";
  }
  out += "title " + quoted(p.title) + "\n";
  out += "firmware " + std::string(p.firmware) + unverified("firmware") + "\n";
  out += "motors " + std::to_string(p.motors) + unverified("motors") + "\n";
  out += "standalone " + std::string(p.standalone ? "yes" : "no") + unverified("standalone") + "\n";
  if (!p.include_file.empty()) out += "include-file " + std::string(p.include_file) + "\n";
  if (p.standalone)
    out += "program-memory " + (p.program_memory > 0 ? std::to_string(p.program_memory) : std::string("unlimited")) +
           (p.program_store == ProgramStore::Eeprom ? " eeprom"
            : p.program_store == ProgramStore::Ram  ? " ram"
                                                    : "") + unverified("program-memory") + "\n";
  out += "user-variables " + std::to_string(p.user_vars) + " eeprom=" + std::to_string(p.eeprom_user_vars) +
         unverified("user-variables") + "\n";
  out += "coordinates " + std::to_string(p.coords) + unverified("coordinates") + "\n";
  out += "parameters " + std::string(p.any_parameter ? "any" : "listed") + "\n";
  out += "motion " + std::string(p.default_motion) +
         (p.fallback_motion.empty() ? "" : " fallback=" + std::string(p.fallback_motion)) + unverified("motion") + "\n";
  for (const auto& c : p.motion_constants) out += "motion-constant " + std::string(c.name) + " " + std::to_string(c.value) + "\n";
  // Commands as ranges of consecutive opcodes.
  std::string commands;
  for (int c = 0; c < 256;) {
    if (!p.commands.test(static_cast<std::size_t>(c))) {
      ++c;
      continue;
    }
    int e = c;
    while (e + 1 < 256 && p.commands.test(static_cast<std::size_t>(e + 1))) ++e;
    commands += " " + std::to_string(c) + (e > c ? "-" + std::to_string(e) : "");
    c = e + 1;
  }
  out += "commands" + (commands.empty() ? std::string(" 255") : commands) + unverified("commands") + "\n";
  if (!p.axis_params.empty()) out += "\n";
  for (const auto& q : p.axis_params) out += "axis " + param(q) + "\n";
  if (!p.bank0.empty()) out += "\n";
  for (const auto& q : p.bank0) out += "global 0 " + param(q) + "\n";
  if (!p.bank3.empty()) out += "\n";
  for (const auto& q : p.bank3) out += "global 3 " + param(q) + "\n";
  if (!p.vectors.empty()) out += "\n";
  for (const auto& v : p.vectors)
    out += "vector " + std::to_string(v.number) + " " + std::string(v.name) + " " + quoted(v.meaning) + "\n";
  return out;
}

}  // namespace tmcl
