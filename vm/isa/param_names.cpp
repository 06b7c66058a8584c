// Parameter names across modules (tmcl/param_names.hpp): the renumbering hint and the generated
// module include files. Both read the profiles only; no module is named here.
#include "tmcl/param_names.hpp"

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
  for (const Profile* other : all_profiles()) {
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
