// Durations ("50us", "10ms", "2s", "1min", "0") and the stable text form of an instant.
#include "tmcl/duration.hpp"

#include <cstdio>

namespace tmcl {

std::optional<SimTime> parse_duration(std::string_view text) {
  std::size_t i = 0;
  SimTime n = 0;
  while (i < text.size() && text[i] >= '0' && text[i] <= '9') {
    if (n > (kNever / 10 - 9) / 60'000'000) return std::nullopt;  // keeps n * unit in range
    n = n * 10 + (text[i] - '0');
    ++i;
  }
  if (i == 0) return std::nullopt;
  std::string_view unit = text.substr(i);
  if (unit.empty()) return n == 0 ? std::optional<SimTime>(0) : std::nullopt;
  if (unit == "us") return n;
  if (unit == "ms") return n * 1000;
  if (unit == "s") return n * 1'000'000;
  if (unit == "min") return n * 60'000'000;
  return std::nullopt;
}

std::string format_time(SimTime t) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%lld.%06llds", static_cast<long long>(t / 1'000'000),
                static_cast<long long>(t % 1'000'000));
  return buf;
}

}  // namespace tmcl
