// The one reader of decimal numbers in text formats (EEPROM files, scenarios, durations): an
// optional sign, digits, and where the caller allows it a decimal fraction, scaled to an exact
// integer. It says what is wrong instead of guessing: a fraction that does not come out whole
// in the caller's unit is an error, never rounded.
#pragma once

#include <cstdint>
#include <string_view>

namespace tmcl {

enum class NumberStatus {
  Ok,
  Empty,       // no text at all
  Malformed,   // not [+|-]digits[.digits]
  Negative,    // a minus sign where Decimal::sign is false (a plus sign is Malformed then)
  Fraction,    // a decimal point where Decimal::scale is 1 and fractions are not allowed
  Inexact,     // value * scale is not a whole number
  OutOfRange,  // outside [lo, hi] (after scaling)
};

struct Decimal {
  std::int64_t lo = INT64_MIN, hi = INT64_MAX;  // inclusive bounds of the scaled result
  std::int64_t scale = 1;   // the result is the number times scale ("1.5" with 1000 -> 1500)
  bool fraction = false;    // a decimal point is allowed (the scaled result must still be whole)
  bool sign = true;         // a leading '+' or '-' is allowed
};

// Parses all of `text`; on Ok sets `out`. Digits only: no spaces, hex, exponents or '_'.
NumberStatus parse_decimal(std::string_view text, const Decimal& rules, std::int64_t& out);

// A decimal integer in [lo, hi] (signed), the common case.
inline bool parse_int(std::string_view text, std::int64_t lo, std::int64_t hi, std::int64_t& out) {
  return parse_decimal(text, Decimal{lo, hi, 1, false, true}, out) == NumberStatus::Ok;
}

}  // namespace tmcl
