// The deviation trip of the shaft model (shaft.hpp): the exact step at which XACTUAL - 209 leaves
// the band of axis parameter 212.
#include "shaft.hpp"

namespace tmcl::shaft {

std::optional<std::int64_t> Deviation::trip(std::int64_t x0, int dir, std::int64_t max) const {
  auto beyond = [&](std::int64_t x) {
    const std::int64_t d = at(x);
    return d > max || d < -max;
  };
  if (beyond(x0)) return x0;
  constexpr std::int64_t kReach = std::int64_t{1} << 40;
  std::int64_t ok = 0, bad = kReach;  // distances from x0 in `dir`
  if (!beyond(x0 + dir * bad)) return std::nullopt;
  while (bad - ok > 1) {
    const std::int64_t mid = ok + (bad - ok) / 2;
    (beyond(x0 + dir * mid) ? bad : ok) = mid;
  }
  return x0 + dir * bad;
}

}  // namespace tmcl::shaft
