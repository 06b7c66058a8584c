// Durations ("50us", "10ms", "1.5s", "2min", "1h", "0") and the stable text form of an instant.
// The number is read by the one decimal reader (numbers.hpp), scaled to microseconds exactly.
#include "tmcl/duration.hpp"

#include <cstdio>

#include "tmcl/numbers.hpp"

namespace tmcl {

namespace {

struct Unit {
  std::string_view name;
  SimTime us;
};
constexpr Unit kUnits[] = {{"us", 1}, {"ms", 1000}, {"s", 1'000'000}, {"min", 60'000'000}, {"h", 3'600'000'000}};
constexpr const char* kUnitList = "us, ms, s, min or h";

}  // namespace

std::optional<SimTime> parse_duration(std::string_view text, std::string& error) {
  const std::string quoted = "'" + std::string(text) + "'";
  if (text.empty()) {
    error = "empty duration; use a number with " + std::string(kUnitList) + " (e.g. 10ms, 1.5s)";
    return std::nullopt;
  }
  // The unit is the trailing run of letters; the number is everything before it.
  std::size_t split = text.size();
  while (split > 0 && ((text[split - 1] >= 'a' && text[split - 1] <= 'z') || (text[split - 1] >= 'A' && text[split - 1] <= 'Z')))
    --split;
  std::string_view number = text.substr(0, split), unit = text.substr(split);
  if (number.empty()) {
    error = quoted + " has no number before its unit";
    return std::nullopt;
  }
  SimTime scale = 0;
  for (const auto& u : kUnits)
    if (unit == u.name) scale = u.us;
  if (!unit.empty() && scale == 0) {
    error = "unknown unit '" + std::string(unit) + "' in " + quoted + "; use " + kUnitList;
    return std::nullopt;
  }
  std::int64_t value = 0;
  NumberStatus st = parse_decimal(number, Decimal{0, kNever - 1, unit.empty() ? 1 : scale, true, false}, value);
  if (st == NumberStatus::Ok && unit.empty() && value != 0) {
    error = quoted + " needs a unit: " + kUnitList + " (only 0 may go without one)";
    return std::nullopt;
  }
  switch (st) {
    case NumberStatus::Ok: return value;
    case NumberStatus::Negative: error = quoted + " is negative; a duration is 0 or more"; break;
    case NumberStatus::Inexact: error = std::string(text) + " is not a whole number of microseconds"; break;
    case NumberStatus::OutOfRange: error = quoted + " is too long (at most about 292,000 years)"; break;
    case NumberStatus::Empty:
    case NumberStatus::Malformed:
    case NumberStatus::Fraction:
      if (unit.empty() && number.find_first_not_of("0123456789.+-") != std::string_view::npos)
        error = quoted + " is not a duration; use a number with " + kUnitList + " (e.g. 10ms, 1.5s)";
      else
        error = "malformed number '" + std::string(number) + "' in " + quoted + " (digits, optionally with a decimal point: 1.5s)";
      break;
  }
  return std::nullopt;
}

std::optional<SimTime> parse_duration(std::string_view text) {
  std::string ignored;
  return parse_duration(text, ignored);
}

std::string format_time(SimTime t) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%lld.%06llds", static_cast<long long>(t / 1'000'000),
                static_cast<long long>(t % 1'000'000));
  return buf;
}

}  // namespace tmcl
