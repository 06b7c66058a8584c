// Durations on the command line and in scenarios: a number with a unit, us, ms, s, min or h
// ("50us", "10ms", "1.5s", "2min", "1h"); "0" needs no unit. The number may have a decimal
// fraction as long as the duration is a whole number of microseconds ("0.25ms" yes,
// "1.0000005ms" no). Simulated time is in microseconds.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "tmcl/sim_time.hpp"

namespace tmcl {

std::optional<SimTime> parse_duration(std::string_view text);
// The same; on failure `error` says exactly what is wrong, e.g. "unknown unit 'x' in '5x'; use
// us, ms, s, min or h" (no file or option name: the caller adds where the text came from).
std::optional<SimTime> parse_duration(std::string_view text, std::string& error);
// Formats an instant as seconds with six decimals ("12.000020s"): exact and stable.
std::string format_time(SimTime t);

}  // namespace tmcl
