// Lookups over the module profile tables in vm/profiles/.
#include "tmcl/profile.hpp"

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
