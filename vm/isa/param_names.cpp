// Parameter names across modules (tmcl/param_names.hpp): the renumbering hint and the generated
// module include files. Both read the profiles only; no module is named here.
#include "tmcl/param_names.hpp"
#include "tmcl/targets.hpp"

#include <algorithm>
#include <cctype>

namespace tmcl {
namespace {

std::span<const ParamInfo> table_of(const Profile& p, ParamTable t) {
  switch (t) {
    case ParamTable::Axis: return p.axis_params;
    case ParamTable::Bank0: return p.bank0;
    case ParamTable::Bank3: return p.bank3;
  }
  return {};
}

const ParamInfo* find_in(std::span<const ParamInfo> table, int number) {
  for (const auto& p : table)
    if (p.number == number) return &p;
  return nullptr;
}

// The words of a name, lower case: "Chopper off time (TOff)" -> chopper, off, time, toff.
std::vector<std::string> words(std::string_view name) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c))) {
      cur += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (!cur.empty()) {
      out.push_back(cur);
      cur.clear();
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

// 2: the same words; 1: at least two words shared and at most one word differing on each side
// ("Soft stop flag", "Soft stop enable"); 0: unrelated.
int nearness(std::string_view a, std::string_view b) {
  auto wa = words(a), wb = words(b);
  if (wa == wb) return 2;
  std::sort(wa.begin(), wa.end());
  std::sort(wb.begin(), wb.end());
  wa.erase(std::unique(wa.begin(), wa.end()), wa.end());
  wb.erase(std::unique(wb.begin(), wb.end()), wb.end());
  std::vector<std::string> shared;
  std::set_intersection(wa.begin(), wa.end(), wb.begin(), wb.end(), std::back_inserter(shared));
  const std::size_t n = shared.size();
  return n >= 2 && wa.size() - n <= 1 && wb.size() - n <= 1 ? 1 : 0;
}

}  // namespace

std::vector<Renumbered> renumbered(const Profile& profile, ParamTable table, int number) {
  std::vector<Renumbered> out;
  const auto here = table_of(profile, table);
  for (const Profile* other : found_profiles()) {
    if (other->any_parameter || other->name == profile.name) continue;
    const auto there = table_of(*other, table);
    const ParamInfo* meant = find_in(there, number);
    if (!meant) continue;
    // The parameters here nearest to the name there; only one may be the nearest.
    const ParamInfo* best = nullptr;
    int best_near = 0;
    bool tie = false;
    for (const auto& q : here) {
      if (q.number == number) continue;
      const int near = nearness(meant->name, q.name);
      if (near == 0 || near < best_near) continue;
      // Mutual: the other module must not have a parameter of its own as near to q's name.
      const bool claimed = std::any_of(there.begin(), there.end(), [&](const ParamInfo& r) {
        return r.number != number && nearness(r.name, q.name) >= near;
      });
      if (claimed) continue;
      tie = near == best_near;
      best = &q, best_near = near;
    }
    if (!best || tie) continue;
    auto same = std::find_if(out.begin(), out.end(), [&](const Renumbered& r) { return r.here == best && r.name == meant->name; });
    if (same != out.end()) same->elsewhere.push_back(other);
    else out.push_back({best, meant->name, {other}, best_near == 2});
  }
  return out;
}

}  // namespace tmcl

namespace tmcl {

std::string parameter_constant(const ParamInfo& p) {
  std::string out, word;
  int depth = 0;
  bool first = true;
  auto flush = [&] {
    if (word.empty()) return;
    std::string low = word;
    for (char& c : low) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (!(first && word == "TMCL")) {
      if (low == "maximum") word = "Max";
      else if (low == "minimum") word = "Min";
      word[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(word[0])));
      out += word;
    }
    first = false;
    word.clear();
  };
  for (char c : p.name) {
    if (c == '(') ++depth;
    if (depth == 0 && std::isalnum(static_cast<unsigned char>(c))) word += c;
    else flush();
    if (c == ')' && depth > 0) --depth;
  }
  flush();
  return out;
}

namespace {

// The include files are ASCII, as TMCL-IDE's are: "μsteps" as "usteps", "pps²" as "pps^2", "pps³"
// (bows) as "pps^3".
std::string ascii_unit(std::string_view unit) {
  std::string out;
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const std::string_view rest = unit.substr(i);
    if (rest.starts_with("\u03bc") || rest.starts_with("\u00b5")) out += 'u', ++i;  // two bytes each
    else if (rest.starts_with("\u00b2")) out += "^2", ++i;
    else if (rest.starts_with("\u00b3")) out += "^3", ++i;
    else if (static_cast<unsigned char>(unit[i]) < 0x80) out += unit[i];
  }
  return out;
}

}  // namespace

std::string parameter_include_name(const Profile& profile) {
  if (!profile.include_file.empty()) return std::string(profile.include_file);
  std::string name(profile.name);
  for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return name + ".inc";
}

std::string parameter_include_text(const Profile& profile) {
  const std::string file = parameter_include_name(profile);
  std::string text = "// " + file + " - parameter numbers of the " + std::string(profile.title) +
                     ",\n// generated by tmcl from its profile (docs/profiles.md, \"Bundled include files\").\n"
                     "// AP_<Name> axis parameter (SAP/GAP/AAP), GP_<Name> global parameter of bank 0,\n"
                     "// GP3_<Name> interrupt setting of bank 3 (SGP/GGP/AGP): <Name> is the manual's name in\n"
                     "// CamelCase. They can be included beside TMCLParam.tmc and Interrupts.inc.\n";
  auto table = [&](std::span<const ParamInfo> params, const char* prefix, const char* heading) {
    if (params.empty()) return;
    text += std::string("\n// ") + heading + "\n";
    for (const ParamInfo& p : params) {
      std::string line = prefix + parameter_constant(p) + " = " + std::to_string(p.number);
      std::string note = std::string(p.name);
      if (!(p.access & kWrite)) note += ", read only";
      if (!p.unit.empty()) note += ", " + ascii_unit(p.unit);
      if (line.size() < 38) line.resize(38, ' ');
      else line += ' ';
      text += line + "// " + note + "\n";
    }
  };
  table(profile.axis_params, "AP_", "Axis parameters");
  table(profile.bank0, "GP_", "Global parameters, bank 0");
  table(profile.bank3, "GP3_", "Interrupt settings, bank 3");
  return text;
}

}  // namespace tmcl
