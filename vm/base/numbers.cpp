// Decimal numbers as text (numbers.hpp). The digits are read into an unsigned 64-bit mantissa
// and a count of decimals; the scaled value mantissa * scale / 10^decimals is computed after
// dividing out their common factors, so "0.25" with scale 1000 is exactly 250 and
// "1.0000005" with scale 1000 is reported as inexact rather than rounded.
#include "tmcl/numbers.hpp"

#include <cstdint>
#include <limits>
#include <numeric>

namespace tmcl {

NumberStatus parse_decimal(std::string_view text, const Decimal& rules, std::int64_t& out) {
  if (text.empty()) return NumberStatus::Empty;
  std::size_t i = 0;
  bool negative = false;
  if (text[0] == '+' || text[0] == '-') {
    negative = text[0] == '-';
    i = 1;
  }
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t mantissa = 0;
  int decimals = 0;
  bool overflow = false, digits_before = false, digits_after = false, point = false;
  for (; i < text.size(); ++i) {
    char c = text[i];
    if (c == '.' && !point) {
      point = true;
      continue;
    }
    if (c < '0' || c > '9') return NumberStatus::Malformed;
    (point ? digits_after : digits_before) = true;
    auto d = static_cast<std::uint64_t>(c - '0');
    if (point) ++decimals;
    if (mantissa > (kMax - d) / 10) {
      // Too many digits: only harmless when they are zeros after the point.
      if (!(point && d == 0)) overflow = true;
      else --decimals;
      continue;
    }
    mantissa = mantissa * 10 + d;
  }
  if (!digits_before || (point && !digits_after)) return NumberStatus::Malformed;
  if (negative && !rules.sign) return NumberStatus::Negative;
  if (text[0] == '+' && !rules.sign) return NumberStatus::Malformed;
  if (point && !rules.fraction) return NumberStatus::Fraction;
  if (overflow) return NumberStatus::OutOfRange;
  // Drop trailing zeros of the fraction: 1.500 is 15 tenths.
  while (decimals > 0 && mantissa % 10 == 0) {
    mantissa /= 10;
    --decimals;
  }
  if (decimals > 18) return NumberStatus::Inexact;  // no scale this small divides 10^19
  std::uint64_t divisor = 1;
  for (int k = 0; k < decimals; ++k) divisor *= 10;
  auto scale = static_cast<std::uint64_t>(rules.scale > 0 ? rules.scale : 1);
  std::uint64_t g = std::gcd(scale, divisor);
  scale /= g;
  divisor /= g;
  if (mantissa % divisor != 0) return NumberStatus::Inexact;
  std::uint64_t whole = mantissa / divisor;
  if (scale != 0 && whole > kMax / scale) return NumberStatus::OutOfRange;
  std::uint64_t magnitude = whole * scale;
  // Into int64 with the sign, then the caller's bounds.
  constexpr auto kMaxPos = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  if (magnitude > kMaxPos + (negative ? 1 : 0)) return NumberStatus::OutOfRange;
  std::int64_t value = negative ? (magnitude == kMaxPos + 1 ? std::numeric_limits<std::int64_t>::min()
                                                              : -static_cast<std::int64_t>(magnitude))
                                : static_cast<std::int64_t>(magnitude);
  if (value < rules.lo || value > rules.hi) return NumberStatus::OutOfRange;
  out = value;
  return NumberStatus::Ok;
}

}  // namespace tmcl
