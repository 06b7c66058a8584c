// What the parameters' names say across modules, derived from the profiles alone: where another
// module found (bundled, or a user's profile on the search path) numbers a parameter under a name this module has at another number (the
// assembler's hint for `SAP 149` on a module whose soft stop is 26), and the include file that
// names one module's parameters (`#include TMCM-1260.inc`, docs/profiles.md).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "tmcl/profile.hpp"

namespace tmcl {

// A parameter kind: axis parameters, or the global parameters of bank 0 or bank 3.
enum class ParamTable { Axis, Bank0, Bank3 };

// One answer of renumbered(): on the modules `elsewhere` the number means `name`; the parameter
// of that name on the module asked about is `here` (same_name: the names are equal; otherwise
// they are one word apart, as "Soft stop flag" and "Soft stop enable").
struct Renumbered {
  const ParamInfo* here;
  std::string_view name;                 // the name on the other modules
  std::vector<const Profile*> elsewhere;  // in found_profiles() order (a user's, then the bundled)
  bool same_name;
};

// For a parameter `number` that `profile` lacks: the parameters of `profile` that other modules
// found (found_profiles(): the search path's, then the bundled) number `number`, matched by name. A match must be mutual: the other module has no
// parameter of its own that is as near to the name here (so "Right limit switch polarity" of
// one module never points at "Right limit switch state", which that module also has).
std::vector<Renumbered> renumbered(const Profile& profile, ParamTable table, int number);

// The constant an include file gives a parameter: the manual's name in CamelCase, parts in
// parentheses dropped, "Maximum"/"Minimum" as "Max"/"Min", a leading "TMCL" dropped. That no
// name means two numbers across the bundled files is tested (profiles_test).
std::string parameter_constant(const ParamInfo& p);

// The bundled include file of a profile: its `include-file`, else NAME.inc in capitals
// ("TMCM-1260.inc"); and its text, one AP_/GP_/GP3_ definition per parameter of the profile.
std::string parameter_include_name(const Profile& profile);
std::string parameter_include_text(const Profile& profile);

}  // namespace tmcl
