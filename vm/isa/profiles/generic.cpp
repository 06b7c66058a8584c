// The generic profile: used when no module is named. It accepts every opcode of opcodes.def
// and every parameter number without range or access checks, so any TMCL program assembles
// and runs. It drives six motors with the same motion core as the USB-2-SD and borrows that
// module's parameter tables and interrupt vectors, for parameter names and power-on defaults
// (a parameter number outside them starts at 0). See docs/profiles.md.
#include <span>

#include "profiles.hpp"
#include "tmcl/isa.hpp"

namespace tmcl::profiles {

// Defined in usb2sd.cpp.
extern const std::span<const ParamInfo> kUsb2SdAxisParams;
extern const std::span<const ParamInfo> kUsb2SdBank0;
extern const std::span<const ParamInfo> kUsb2SdBank3;
extern const std::span<const InterruptVector> kUsb2SdVectors;

namespace {
std::bitset<256> every_opcode() {
  std::bitset<256> b;
  for (const auto& op : all_ops()) b.set(op.code);
  return b;
}
}  // namespace

const Profile kGeneric{
    .name = "generic",
    .title = "generic (any TMCL module)",
    .commands = every_opcode(),
    .any_parameter = true,
    .axis_params = kUsb2SdAxisParams,
    .bank0 = kUsb2SdBank0,
    .bank3 = kUsb2SdBank3,
    .user_vars = 256,  // user variables
    .eeprom_user_vars = 56,  // EEPROM-backed user variables
    .coords = 21,  // coordinates 0..20 per motor
    .vectors = kUsb2SdVectors,
    .program_memory = 0,  // program memory: unlimited
    .motors = 6,  // Motor0..Motor5 of TMCLParam.tmc
    .default_motion = "tmc4361",
    .firmware = "0000V100",
};

}  // namespace tmcl::profiles
