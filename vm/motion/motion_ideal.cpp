// The `ideal` motion core: infinite acceleration. A move completes at the instant it is
// commanded (the target-reached event carries that instant); rotation runs at the commanded
// speed from that instant, so the position is a closed-form line p0 + v * (t - t0). Enough for
// logic tests of programs; the real ramp generators are separate cores (motion.hpp).
//
// Parameters it owns: 0 target, 1 actual position, 2 target speed, 3 actual speed,
// 8 position reached, 127 relative positioning option, 209 encoder position, 212 maximum
// encoder deviation. Stop and home switches do not stop an ideal motor (documented).
//
// It shares the skeleton of every core (core_skeleton.hpp: owned parameters with the profile's
// defaults and ranges, events a command causes), not RampCore's plans: a plan is a continuous
// motion in double-precision seconds and steps, and an ideal motor jumps. Its position is an
// exact integer line instead, so after hours of rotation it is still the exact step count that
// p0 + v * t gives, which a plan's floating-point segment would not promise (docs/motion.md).
#include <array>
#include <cstdlib>

#include "core_skeleton.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"

namespace tmcl {
namespace {

constexpr SimTime kUsPerSecond = 1'000'000;

std::int32_t wrap32(std::int64_t v) { return static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(v))); }

constexpr int kOwned[] = {kApTargetPosition, kApActualPosition,           kApTargetSpeed,     kApActualSpeed,
                          kApPositionReached, kApRelativePositioningOption, kApEncoderPosition, kApMaxEncoderDeviation};

struct Motor {
  std::array<std::int32_t, 256> p{};  // owned parameters: 127 and 212 are kept here
  std::int64_t base = 0;     // position at t0 (not wrapped; reads wrap to 32 bits)
  SimTime t0 = 0;
  std::int32_t velocity = 0; // pps; 0 in position mode
  std::int32_t target = 0;
  std::int64_t encoder_offset = 0;  // encoder position - actual position
};

class IdealCore final : public CoreSkeleton<Motor> {
 public:
  std::string_view name() const override { return "ideal"; }
  std::unique_ptr<MotionCore> clone() const override { return std::make_unique<IdealCore>(*this); }

  // The ideal core models no particular module: where a profile lacks 127 or 212 the USB-2-SD's
  // rows stand in (both default to 0, the power-on state of an ideal motor).
  IdealCore() : CoreSkeleton(kOwned, "usb-2-sd") {}

  SimTime next_event() const override { return next_pending(); }

  void advance(SimTime to, std::vector<MotionEvent>& out) override {
    if (to > now_) now_ = to;
    take_pending(out);
  }

  ParamWrite set_param(int motor, int param, std::int32_t value) override {
    Motor& m = at(motor);
    switch (param) {
      case kApTargetPosition: move_absolute(motor, value); return ParamWrite::Ok;
      case kApActualPosition:
        rebase(m);
        m.base = value;
        return ParamWrite::Ok;
      case kApTargetSpeed: rotate(motor, value); return ParamWrite::Ok;
      case kApRelativePositioningOption:
      case kApMaxEncoderDeviation:  // within the profile's range (core_skeleton.hpp)
        if (!in_range(param, value)) return ParamWrite::OutOfRange;
        m.p[static_cast<std::size_t>(param)] = value;
        return ParamWrite::Ok;
      case kApEncoderPosition: m.encoder_offset = static_cast<std::int64_t>(value) - pos(m); return ParamWrite::Ok;
      default: return ParamWrite::ReadOnly;
    }
  }

  std::int32_t get_param(int motor, int param) override {
    Motor& m = at(motor);
    switch (param) {
      case kApTargetPosition: return m.target;
      case kApActualPosition: return wrap32(pos(m));
      case kApTargetSpeed: return m.velocity;
      case kApActualSpeed: return m.velocity;
      case kApPositionReached: return target_reached(motor) ? 1 : 0;
      case kApRelativePositioningOption: case kApMaxEncoderDeviation: return m.p[static_cast<std::size_t>(param)];
      case kApEncoderPosition: return wrap32(pos(m) + m.encoder_offset);
      default: return 0;
    }
  }

  void move_absolute(int motor, std::int32_t target) override {
    Motor& m = at(motor);
    rebase(m);
    m.velocity = 0;
    m.target = target;
    m.base = target;
    emit(motor, MotionEventKind::TargetReached, m);
  }

  void rotate(int motor, std::int32_t velocity) override {
    Motor& m = at(motor);
    rebase(m);
    m.velocity = velocity;
    emit(motor, velocity == 0 ? MotionEventKind::Stopped : MotionEventKind::VelocityReached, m);
  }

  void stop(int motor) override {
    Motor& m = at(motor);
    bool was_moving = m.velocity != 0;
    rebase(m);
    m.velocity = 0;
    if (was_moving) emit(motor, MotionEventKind::Stopped, m);
  }

  std::int32_t reference_search(int motor, RfsAction action) override {
    Motor& m = at(motor);
    if (action == RfsAction::Start) {  // completes at once: the home is where the motor is
      rebase(m);
      m.velocity = 0;
      m.base = 0;
      m.target = 0;
      m.encoder_offset = 0;
      emit(motor, MotionEventKind::ReferenceDone, m);
    }
    return 0;
  }

  void set_switch(int, SwitchInput, bool) override {}

  bool models_encoder(const Profile&) const override { return true; }
  void encoder_slip(int motor, std::int32_t counts) override {
    Motor& m = at(motor);
    m.encoder_offset += counts;
    const std::int32_t max_deviation = m.p[kApMaxEncoderDeviation];
    if (max_deviation > 0 && std::llabs(m.encoder_offset) > max_deviation) {
      rebase(m);
      m.velocity = 0;
      m.target = wrap32(m.base);
      emit(motor, MotionEventKind::Deviation, m);
    }
  }

  std::int32_t position(int motor) const override { return wrap32(pos(motors_[static_cast<std::size_t>(motor)])); }
  bool target_reached(int motor) const override {
    const Motor& m = motors_[static_cast<std::size_t>(motor)];
    return m.velocity == 0 && wrap32(pos(m)) == m.target;
  }
  bool reference_done(int) const override { return true; }

 private:
  // Position at now_: exact integer arithmetic, truncated toward zero.
  std::int64_t pos(const Motor& m) const {
    if (m.velocity == 0) return m.base;
    SimTime dt = now_ - m.t0;
    std::int64_t v = m.velocity;
    return m.base + v * (dt / kUsPerSecond) + v * (dt % kUsPerSecond) / kUsPerSecond;
  }
  void rebase(Motor& m) {
    m.base = pos(m);
    m.t0 = now_;
  }
  void emit(int motor, MotionEventKind kind, const Motor& m) { report_now(motor, kind, wrap32(pos(m))); }
};

}  // namespace

std::unique_ptr<MotionCore> make_ideal_motion_core() { return std::make_unique<IdealCore>(); }

}  // namespace tmcl
