// Simulated time: an integer count of microseconds, the one clock of the VM, the motion cores
// and every trace. Nothing here reads the wall clock.
#pragma once

#include <cstdint>
#include <limits>

namespace tmcl {

using SimTime = std::int64_t;
inline constexpr SimTime kNever = std::numeric_limits<SimTime>::max();
inline constexpr SimTime kUsPerMs = 1000;
inline constexpr SimTime kUsPerTick = 10 * kUsPerMs;  // one WAIT tick is 10 ms

}  // namespace tmcl
