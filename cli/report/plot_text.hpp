// Number and text formatting shared by the report library's CSV and SVG writers (private).
#pragma once

#include <string>

#include "tmcl/sim_time.hpp"

namespace tmcl::report {

// `decimals` fixed decimals, never "-0.000".
std::string fixed(double v, int decimals);
// Seconds with six decimals, no unit ("1.500000"): exact and stable.
std::string seconds(SimTime t);

}  // namespace tmcl::report
