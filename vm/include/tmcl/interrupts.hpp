// What raises each interrupt vector, in the TMCL numbering every bundled module shares (errata
// E23: timers 0-2, target reached 3+motor, stallGuard 15+motor, deviation 21+motor, stop switches
// 27+2·motor and 28+2·motor, input change 39+input, 255 the global enable), and the one table of
// the vectors the virtual module does not raise (yet), per motion core. The VM raises vectors by
// these numbers; tmclrun's note on EI of a vector that is not simulated, and the test that walks
// every profile's vectors (tests/vm/test_interrupt_sources.cpp), read the same table.
#pragma once

#include <string_view>

#include "tmcl/profile.hpp"

namespace tmcl {

enum class VectorSource : unsigned char {
  Timer,          // bank-3 parameter 0..2 sets the period (ms)
  TargetReached,  // a move reached its target
  PositionCompare,  // the position passed the compare position (TMCM-1290: axis parameters 43, 44)
  Stall,          // stallGuard2 detected a stall
  Deviation,      // the encoder deviates more than axis parameter 212 allows
  StopLeft,       // the left stop switch changed, as bank-3 parameter 27+2·motor selects
  StopRight,      // the right stop switch changed, as bank-3 parameter 28+2·motor selects
  InputChange,    // digital input n (GIO n, 0) changed, as bank-3 parameter 39+n selects
  GlobalEnable,   // 255: EI 255 / DI 255
  Unknown,        // no TMCL source has this number
};

inline constexpr int kVectorTimer0 = 0, kTimerVectors = 3, kVectorTarget0 = 3, kVectorCompare0 = 9, kVectorStall0 = 15, kVectorDeviation0 = 21,
                     kVectorStopLeft0 = 27, kVectorInput0 = 39, kVectorGlobal = 255;

struct VectorKind {
  VectorSource source;
  int index;  // the timer, motor or input; 0 for the others
};
// The source of vector n by number alone (the numbering above; a motor up to 6, an input up to 7,
// as the TMCL modules number them). The profile says which of them a module has.
VectorKind vector_kind(int n);
// "stallGuard2 stall of motor 0": what raises it, in words.
std::string vector_source_text(VectorKind k);

// Why the virtual module does not raise vector n of `profile` when it runs motion core `core`,
// or empty when it does (the vector's source is simulated, and the module has the motor, timer
// or input it names). A vector of an unknown source is never raised.
std::string not_simulated_reason(const Profile& profile, std::string_view core, int n);

}  // namespace tmcl
