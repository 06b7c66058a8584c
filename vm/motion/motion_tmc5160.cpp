// The `tmc5160` motion core: the ramp generator of the TMCM-1260 (PD57-1260, PD60-1260), a
// TMC5160, as the module's firmware manual 1.44 describes it: speeds in pps, accelerations in
// pps². Positioning (MVP) runs the SixPoint ramp (sections 1.3 and 7.5): from VSTART (19) with A1
// (15) up to V1 (16), with A2 (5) up to VMAX (4); down with D2 (17) to V1, with D1 (18) to VSTOP
// (20); V1 = 0 leaves A2 and D2 alone. Velocity mode (ROR, ROL, MST) ramps with A2 both ways,
// from and to standstill. The limit switches with their stop functions (12, 13: disable; 26: soft
// stop) and the reference search (RFS, 193-197, with +64 for the other end switch) are the shared
// part of switch_core.hpp; the home switch has its own input. The ramp itself is shared with the
// `tmc5240` core (tmc5160_family.hpp). docs/motion.md explains every decision, docs/errata.md
// where the manual is silent.
//
// Parameters it owns: 0-13, 15-20, 26, 127, 140, 168-174, 180-182, 193-197, 206, 208, and 207, 209,
// 210, 212 (the SensOstep encoder, switch_core.hpp).
#include "tmc5160_family.hpp"

namespace tmcl {
// Named, so that the two TMC5160-family cores' numbers (kA1, kD2, …) stay apart in a unity build.
namespace tmc5160_core {
namespace {

// The TMCM-1260's number beyond the family's (PD57/60-1260 manual, chapter 4).
enum Tmc5160Param : int {
  kD2 = 17,                // "maximum deceleration"
};
using sw::kA1, sw::kV1, sw::kD1, sw::kVStart, sw::kVStop, sw::kLimitSoftStop, sw::kRelativeOption, sw::kLastReference;

constexpr int kTmc5160Owned[] = {kApTargetPosition, kApActualPosition, kApTargetSpeed, kApActualSpeed,
                                 kApMaxPositioningSpeed, kApMaxAcceleration, kApPositionReached,
                                 sw::kHomeState, sw::kRightSwitchState, sw::kLeftSwitchState,
                                 sw::kRightStopDisable, sw::kLeftStopDisable, kA1, kV1, kD2, kD1, kVStart,
                                 kVStop, kLimitSoftStop, kRelativeOption, sw::kRfsMode, sw::kRfsSpeed,
                                 sw::kRfsSwitchSpeed, sw::kRfsDistance, kLastReference,
                                 sw::kErrorFlags, sw::kEncoderPosition, sw::kEncoderPrescaler, sw::kMaxDeviation,
                                 // stallGuard2 (stall_core.cpp): run current, microsteps, filter, threshold, stop on stall, load value, driver flags
                                 6, 140, 173, 174, 181, 206, 208,
                                 // StealthChop, in which stallGuard2 measures nothing: PWM threshold speed, PWM gradient
                                 186, 187,
                                // coolStep (coolstep_core.cpp): standby current, 168-172, actual current, threshold speed
                                7, 168, 169, 170, 171, 172, 180, 182};

class Tmc5160Core final : public sw::Tmc5160Family {
 public:
  std::string_view name() const override { return "tmc5160"; }
  std::unique_ptr<MotionCore> clone() const override { return std::make_unique<Tmc5160Core>(*this); }

  // Its parameters are in pps like the generic profile's, but numbered as the TMCM-1260 numbers
  // them: under generic its rows come from the TMCM-1260's profile.
  Tmc5160Core()
      : Tmc5160Family(kTmc5160Owned, "tmcm-1260", {kLimitSoftStop, false, true, kLastReference},
                      {kA1, kV1, kD2, kD1, kVStart, kVStop, "A2", "D2"}) {}
};

}  // namespace
}  // namespace tmc5160_core

std::unique_ptr<MotionCore> make_tmc5160_motion_core() { return std::make_unique<tmc5160_core::Tmc5160Core>(); }

}  // namespace tmcl
