// Durations on the command line and in scenarios: an integer with a unit, us, ms, s or min
// ("50us", "10ms", "2s", "1min"); "0" needs no unit. Simulated time is in microseconds.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "tmcl/sim_time.hpp"

namespace tmcl {

std::optional<SimTime> parse_duration(std::string_view text);
// Formats an instant as seconds with six decimals ("12.000020s"): exact and stable.
std::string format_time(SimTime t);

}  // namespace tmcl
