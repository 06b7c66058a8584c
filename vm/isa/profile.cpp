// Lookups over the module profile tables in vm/profiles/.
#include "tmcl/profile.hpp"

#include <cstdint>

#include "profiles/profiles.hpp"

namespace tmcl {
namespace {

const ParamInfo* find_param(std::span<const ParamInfo> table, int number) {
  for (const auto& p : table)
    if (p.number == number) return &p;
  return nullptr;
}

constexpr const Profile* kAll[] = {&profiles::kGeneric, &profiles::kUsb2Sd, &profiles::kTmc2300Eval};

}  // namespace

bool accepts(const ParamInfo& p, std::int64_t value) {
  if (value >= p.min && value <= p.max) return true;
  if (value < INT32_MIN || value > INT32_MAX) return false;
  const auto u = static_cast<std::int64_t>(static_cast<std::uint32_t>(value));
  return u >= p.min && u <= p.max;
}

std::string range_text(const ParamInfo& p) {
  return std::to_string(p.min) + " to " + std::to_string(p.max) + (p.unit.empty() ? "" : " " + std::string(p.unit));
}

std::string param_text(std::string_view kind, int number, const ParamInfo* p) {
  std::string s = std::string(kind) + " " + std::to_string(number);
  if (p && !p->name.empty()) s += " (" + std::string(p->name) + ")";
  return s;
}

const ParamInfo* Profile::axis_param(int number) const { return find_param(axis_params, number); }

const ParamInfo* Profile::global_param(int bank, int number) const {
  if (bank == 0) return find_param(bank0, number);
  if (bank == 3) return find_param(bank3, number);
  return nullptr;
}

const InterruptVector* Profile::vector(int number) const {
  for (const auto& v : vectors)
    if (v.number == number) return &v;
  return nullptr;
}

std::span<const Profile* const> all_profiles() { return kAll; }

std::vector<std::string> profile_names() {
  std::vector<std::string> names;
  for (const Profile* p : kAll) names.emplace_back(p->name);
  return names;
}

const Profile* find_profile(std::string_view name) {
  for (const Profile* p : kAll)
    if (p->name == name) return p;
  return nullptr;
}

const Profile& generic_profile() { return profiles::kGeneric; }

}  // namespace tmcl
