// The built-in profile objects, one per file in this folder; registered in profile.cpp.
#pragma once

#include "tmcl/profile.hpp"

namespace tmcl::profiles {
extern const Profile kGeneric;
extern const Profile kUsb2Sd;
extern const Profile kTmc2300Eval;
}  // namespace tmcl::profiles
