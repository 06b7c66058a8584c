// The sources of the interrupt vectors and the table of those the virtual module does not raise
// (interrupts.hpp). Helpers implementing a source remove its row from kNotSimulated.
#include "tmcl/interrupts.hpp"

#include <string>

namespace tmcl {
namespace {

// A source that no run raises on a core ("*": every core), with the reason a run's note gives.
struct NotSimulated {
  VectorSource source;
  std::string_view core;
  std::string_view why;
  std::string_view unless_constant = {};  // the row does not apply where the profile sets this motion constant
};
constexpr NotSimulated kNotSimulated[] = {
    // the load measurements are modelled by the TMCM cores and the linear core (vm/motion/stall_core.cpp, docs/motion.md)
    // no core models the position compare unit (errata: the TMCM-1290's 43-46)
    {VectorSource::PositionCompare, "*", "no position compare (axis parameters 43, 44) is modelled"},
    {VectorSource::Stall, "ideal", "the ideal core models no load and no stallGuard2"},
    {VectorSource::Stall, "tmc4361", "the tmc4361 core models no load and no stallGuard2"},
    {VectorSource::Deviation, "linear", "the linear core has no encoder model"},
    // the TMCM cores model the encoder where the profile declares one (switch_core.cpp)
    {VectorSource::Deviation, "tmc429", "the profile declares no encoder (motion-constant encoder)", "encoder"},
    {VectorSource::Deviation, "tmc5160", "the profile declares no encoder (motion-constant encoder)", "encoder"},
};

constexpr int kMaxMotors = 6, kMaxInputs = 8;

}  // namespace

VectorKind vector_kind(int n) {
  if (n >= kVectorTimer0 && n < kVectorTimer0 + kTimerVectors) return {VectorSource::Timer, n - kVectorTimer0};
  if (n >= kVectorTarget0 && n < kVectorTarget0 + kMaxMotors) return {VectorSource::TargetReached, n - kVectorTarget0};
  if (n >= kVectorCompare0 && n < kVectorCompare0 + kMaxMotors) return {VectorSource::PositionCompare, n - kVectorCompare0};
  if (n >= kVectorStall0 && n < kVectorStall0 + kMaxMotors) return {VectorSource::Stall, n - kVectorStall0};
  if (n >= kVectorDeviation0 && n < kVectorDeviation0 + kMaxMotors) return {VectorSource::Deviation, n - kVectorDeviation0};
  if (n >= kVectorStopLeft0 && n < kVectorStopLeft0 + 2 * kMaxMotors)
    return {(n - kVectorStopLeft0) % 2 == 0 ? VectorSource::StopLeft : VectorSource::StopRight, (n - kVectorStopLeft0) / 2};
  if (n >= kVectorInput0 && n < kVectorInput0 + kMaxInputs) return {VectorSource::InputChange, n - kVectorInput0};
  if (n == kVectorGlobal) return {VectorSource::GlobalEnable, 0};
  return {VectorSource::Unknown, 0};
}

std::string vector_source_text(VectorKind k) {
  const std::string i = std::to_string(k.index);
  switch (k.source) {
    case VectorSource::Timer: return "timer " + i;
    case VectorSource::TargetReached: return "target position reached of motor " + i;
    case VectorSource::PositionCompare: return "position compare of motor " + i;
    case VectorSource::Stall: return "stallGuard2 stall of motor " + i;
    case VectorSource::Deviation: return "encoder deviation of motor " + i;
    case VectorSource::StopLeft: return "left stop switch of motor " + i;
    case VectorSource::StopRight: return "right stop switch of motor " + i;
    case VectorSource::InputChange: return "change of input " + i;
    case VectorSource::GlobalEnable: return "the global enable";
    case VectorSource::Unknown: break;
  }
  return "nothing known";
}

std::string not_simulated_reason(const Profile& profile, std::string_view core, int n) {
  const VectorKind k = vector_kind(n);
  switch (k.source) {
    case VectorSource::Unknown: return "no TMCL module numbers a source of interrupt " + std::to_string(n);
    case VectorSource::Timer:
    case VectorSource::GlobalEnable: return {};
    case VectorSource::InputChange:
      if (!profile.any_parameter && !profile.digital_input(k.index))
        return "the profile has no digital input " + std::to_string(k.index) + " (GIO " + std::to_string(k.index) + ", 0)";
      break;
    default:
      if (k.index >= profile.motors) return "the module has no motor " + std::to_string(k.index);
      // The stall model runs where the profile has stallGuard2's threshold or names its load
      // measurement (`motion-constant stallguard`, stall_core.cpp).
      if (k.source == VectorSource::Stall && !profile.any_parameter && profile.axis_param(174) == nullptr &&
          profile.motion_constant("stallguard", 0) == 0)
        return "the profile has no stallGuard2 threshold (axis parameter 174), so no stall is modelled";
      break;
  }
  for (const auto& row : kNotSimulated)
    if (row.source == k.source && (row.core == "*" || row.core == core) &&
        (row.unless_constant.empty() || (!profile.any_parameter && profile.motion_constant(row.unless_constant, 0) == 0)))
      return std::string(row.why);
  return {};
}

}  // namespace tmcl
