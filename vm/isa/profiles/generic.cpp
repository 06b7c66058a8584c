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
    "generic",
    "generic (any TMCL module)",
    every_opcode(),
    true,
    kUsb2SdAxisParams,
    kUsb2SdBank0,
    kUsb2SdBank3,
    256,  // user variables
    56,   // EEPROM-backed user variables
    21,   // coordinates 0..20 per motor
    kUsb2SdVectors,
    0,    // program memory: unlimited
    6,    // Motor0..Motor5 of TMCLParam.tmc
    "tmc4361",
    "0000V100",
};

}  // namespace tmcl::profiles
