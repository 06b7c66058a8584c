// The `tmc5240` motion core: the ramp generator of the TMCM-1290 and TMCM-3216, a TMC5240, as
// the TMCM-1290 firmware manual 1.01 describes it: speeds in pps, accelerations in pps².
// Positioning (MVP) runs the EightPoint ramp (sections 1.3, 7.6): from VSTART (19) with A1 (15)
// up to V1 (16), with A2 (34) up to V2 (35), with AMAX (5) up to VMAX (4); down with DMAX (17) to
// V2, with D2 (36) to V1, with D1 (18) to VSTOP (20). V1 = 0 skips A1 and D1, V2 = 0 (or V2 <= V1)
// skips A2 and D2 (parameter 16: "setting this value to 0 turns off the first acceleration/
// deceleration phase"). Velocity mode ramps with AMAX both ways (parameter 5). After the speed
// reached 0 the motor rests the ramp wait time (21, 32 µs units) before it moves again. The
// virtual stops (38, 39, enabled by 41, read in 40) stop a motor moving past them as a limit
// switch does. The ramp is the tmc5160 core's with the middle band (tmc5160_family.hpp); the
// limit switches, the reference search (with the encoder's null-channel modes 9, 10, never met:
// no null channel is modelled), stallGuard2, coolStep and the encoder are switch_core.hpp's.
// docs/motion.md explains every decision.
//
// Parameters it owns: 0-13, 15-21, 26, 34-36, 38-41, 127, 140, 168-174, 180-182, 193-197, 206,
// 208, and 207, 209, 210, 212 (the encoder, switch_core.hpp).
#include "tmc5160_family.hpp"

namespace tmcl {
// Named, so that the two TMC5160-family cores' numbers (kA1, kD2, …) stay apart in a unity build.
namespace tmc5240_core {
namespace {

// The TMCM-1290's numbers beyond the family's (TMCM-1290 manual, table 16).
enum Tmc5240Param : int {
  kDMax = 17,              // "maximum deceleration"
  kRampWait = 21,          // "ramp wait time", 0.000032 s
  kA2 = 34,
  kV2 = 35,
  kD2 = 36,
  kVirtualLeft = 38,
  kVirtualRight = 39,
  kVirtualFlags = 40,      // 0 none, 1 at the left, 2 at the right virtual stop
  kVirtualEnable = 41,     // bit 0 left, bit 1 right
};
using sw::kA1, sw::kV1, sw::kD1, sw::kVStart, sw::kVStop, sw::kLimitSoftStop, sw::kRelativeOption, sw::kLastReference;

constexpr int kTmc5240Owned[] = {kApTargetPosition, kApActualPosition, kApTargetSpeed, kApActualSpeed,
                                 kApMaxPositioningSpeed, kApMaxAcceleration, kApPositionReached,
                                 sw::kHomeState, sw::kRightSwitchState, sw::kLeftSwitchState,
                                 sw::kRightStopDisable, sw::kLeftStopDisable, kA1, kV1, kDMax, kD1, kVStart,
                                 kVStop, kRampWait, kLimitSoftStop, kA2, kV2, kD2, kVirtualLeft, kVirtualRight,
                                 kVirtualFlags, kVirtualEnable, kRelativeOption, sw::kRfsMode, sw::kRfsSpeed,
                                 sw::kRfsSwitchSpeed, sw::kRfsDistance, kLastReference,
                                 sw::kErrorFlags, sw::kEncoderPosition, sw::kEncoderPrescaler, sw::kMaxDeviation,
                                 // stallGuard2 (stall_core.cpp): run current, microsteps, filter, threshold, stop on stall, load value, driver flags
                                 6, 140, 173, 174, 181, 206, 208,
                                 // coolStep (coolstep_core.cpp): standby current, 168-172, actual current, threshold speed
                                 7, 168, 169, 170, 171, 172, 180, 182};

sw::SwitchConfig switch_config() {
  sw::SwitchConfig c{kLimitSoftStop, false, true, kLastReference};
  c.null_channel = true;    // modes 9, 10 (table 22)
  c.mode7_negative = true;  // table 22 and section 7.1.7 (errata)
  return c;
}

class Tmc5240Core final : public sw::Tmc5160Family {
 public:
  std::string_view name() const override { return "tmc5240"; }
  std::unique_ptr<MotionCore> clone() const override { return std::make_unique<Tmc5240Core>(*this); }

  // Under generic its rows come from the TMCM-1290's profile.
  Tmc5240Core()
      : Tmc5160Family(kTmc5240Owned, "tmcm-1290", switch_config(),
                      {kA1, kV1, kDMax, kD1, kVStart, kVStop, "AMAX", "DMAX", kA2, kV2, kD2, kRampWait}) {}

  // 40 is read-only here (which virtual stop the motor is at); a module whose row 40 is
  // writable means another parameter by it (the TMCM-6214's position compare start): under such
  // a profile the core leaves 40 to the VM, which stores it as the profile says.
  void reset(const Profile& profile, int motors) override {
    Tmc5160Family::reset(profile, motors);
    const ParamInfo* row = profile.axis_param(kVirtualFlags);
    flags_owned_ = !row || !(row->access & kWrite);
  }
  bool owns(int param) const override { return (param != kVirtualFlags || flags_owned_) && Tmc5160Family::owns(param); }

  std::int32_t get_param(int motor, int param) override {
    if (param != kVirtualFlags) return Tmc5160Family::get_param(motor, param);
    const sw::Motor& m = at(motor);
    const std::int64_t x = m.rm.xactual(now_);
    const int en = m.p[kVirtualEnable];
    if ((en & 1) && x <= m.p[kVirtualLeft]) return 1;
    if ((en & 2) && x >= m.p[kVirtualRight]) return 2;
    return 0;
  }

 protected:
  ParamWrite set_other(sw::Motor& m, int param, std::int32_t value) override {
    if (param == kVirtualFlags) return ParamWrite::ReadOnly;
    return Tmc5160Family::set_other(m, param, value);
  }

  // A virtual stop enabled in 41 stops a motor moving toward it at the instant its position
  // reaches it (left: moving -, XACTUAL <= 38; right: moving +, XACTUAL >= 39), as a limit switch
  // does (26: soft or hard); moving away from it is free. docs/motion.md, "Virtual stops".
  void scan_stops(sw::Motor& m, const ramp::Limits& lim) override {
    const int en = m.p[kVirtualEnable];
    if ((en & 3) == 0) return;
    for (const auto& seg : m.rm.plan.segs) {
      if (seg.t0 >= m.trip_t) return;
      if (seg.dir == 0) continue;
      const bool right = seg.dir > 0;
      if (!(en & (right ? 2 : 1))) continue;
      const double k = static_cast<double>(std::int64_t{m.p[right ? kVirtualRight : kVirtualLeft]} - m.rm.base);
      const double dt = ramp::crossing(seg, k);
      if (dt < 0 || seg.t0 + dt >= m.trip_t) continue;
      return stop_at(m, seg.t0 + dt, lim);
    }
  }

 private:
  bool flags_owned_ = true;
};

}  // namespace
}  // namespace tmc5240_core

std::unique_ptr<MotionCore> make_tmc5240_motion_core() { return std::make_unique<tmc5240_core::Tmc5240Core>(); }

}  // namespace tmcl
