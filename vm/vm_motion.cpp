// The motion commands (MVP, ROR/ROL, MST, RFS) with the module profile's rules: each checks the
// motor and its operands, brings the motion core to the present instant and hands it the move.
// Each returns a direct-mode status; standalone mode ignores a command whose status is not 100 (E3).
#include <cstdint>

#include "tmcl/params.hpp"
#include "tmcl/vm.hpp"

namespace tmcl {

std::uint8_t Vm::move(int type, int motor, std::int32_t value) {
  if (!motor_ok(motor)) return kStatusInvalidValue;
  sync_motion();
  switch (type) {
    case kw::Move::ABS: motion->move_absolute(motor, value); break;
    case kw::Move::REL: motion->move_relative(motor, value); break;
    case kw::Move::COORD:
      // A module without coordinates has no COORD type (the TMC2300-MOTOR-EVAL: errata M32).
      if (profile->coords == 0) return kStatusWrongType;
      if (value < 0 || value >= profile->coords) return kStatusInvalidValue;
      motion->move_absolute(motor, coords[static_cast<std::size_t>(motor)][static_cast<std::size_t>(value)]);
      break;
    default: return kStatusWrongType;
  }
  next_check_ = 0;
  return kStatusOk;
}

std::uint8_t Vm::rotate(int motor, std::int64_t velocity) {
  if (!motor_ok(motor)) return kStatusInvalidValue;
  const ParamInfo* p = profile->axis_param(kApTargetSpeed);
  if (p ? !accepts(*p, velocity) : (velocity < INT32_MIN || velocity > INT32_MAX)) return kStatusInvalidValue;
  sync_motion();
  motion->rotate(motor, static_cast<std::int32_t>(velocity));
  next_check_ = 0;
  return kStatusOk;
}

std::uint8_t Vm::motor_stop(int motor) {
  if (!motor_ok(motor)) return kStatusInvalidValue;
  sync_motion();
  motion->stop(motor);
  next_check_ = 0;
  return kStatusOk;
}

std::uint8_t Vm::rfs(int type, int motor, std::int32_t& value) {
  if (!motor_ok(motor)) return kStatusInvalidValue;
  if (type > kw::Rfs::STATUS) return kStatusWrongType;
  static_assert(static_cast<int>(RfsAction::Start) == kw::Rfs::START && static_cast<int>(RfsAction::Stop) == kw::Rfs::STOP &&
                static_cast<int>(RfsAction::Status) == kw::Rfs::STATUS);
  sync_motion();
  value = motion->reference_search(motor, static_cast<RfsAction>(type));
  next_check_ = 0;
  return kStatusOk;
}

}  // namespace tmcl
