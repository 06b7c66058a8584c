// Profile of the USB-2-SD (TMCL firmware 1.14): a one-axis step/direction ramp generator with
// an ABN encoder input, USB powered, program memory in RAM only. Source: the USB-2-SD TMCL
// firmware manual, fw 1.14, document rev 1.01. Parameters the manual uses in its text but leaves
// out of its tables are added and marked "not in table"; every default the manual does not give,
// and every correction of the manual, is explained in docs/profiles.md.
#include <cstdint>
#include <initializer_list>
#include <span>

#include "profiles.hpp"

namespace tmcl::profiles {
namespace {

constexpr std::uint8_t R = kRead;
constexpr std::uint8_t RW = kRead | kWrite;
constexpr std::uint8_t RWA = kRead | kWrite | kAutoStore;

constexpr std::int64_t kI32Min = -2147483648LL;
constexpr std::int64_t kI32Max = 2147483647LL;
constexpr std::int64_t kU32Max = 4294967295LL;
constexpr std::int64_t kVelMax = 16777215;  // 2^24 - 1 pps (the manual prints 1677215 in places)

std::bitset<256> opcodes(std::initializer_list<int> codes) {
  std::bitset<256> b;
  for (int c : codes) b.set(static_cast<std::size_t>(c));
  return b;
}

// Table 14, plus 140, 201 and 255 from sections 6.1 and 6.2.
constexpr ParamInfo kAxis[] = {
    {0, "Target position", kI32Min, kI32Max, RW, 0, "μsteps"},
    {1, "Actual position", kI32Min, kI32Max, RW, 0, "μsteps"},
    {2, "Target speed", -kVelMax, kVelMax, RW, 0, "pps"},
    {3, "Actual speed", -kVelMax, kVelMax, R, 0, "pps"},
    {4, "Maximum positioning speed", 0, kVelMax, RW, 51200, "pps"},
    {5, "Maximum acceleration", 0, kI32Max, RW, 51200, "pps²"},
    {8, "Position reached flag", 0, 1, R, 1, ""},
    {14, "Ramp type", 0, 1, RW, 0, ""},
    {15, "Start velocity", 0, kVelMax, RW, 0, "pps"},
    {16, "Start acceleration", 0, kI32Max, RW, 0, "pps²"},     // 0: same as 5
    {17, "Maximum deceleration", 0, kI32Max, RW, 0, "pps²"},   // 0: same as 5
    {18, "Break velocity", 0, kVelMax, RW, 0, "pps"},  // 0: no break point; the table says pps² for a velocity
    {19, "Final deceleration", 0, kI32Max, RW, 0, "pps²"},     // 0: same as 17
    {20, "Stop velocity", 0, kVelMax, RW, 0, "pps"},
    {21, "Stop deceleration", 0, kI32Max, RW, 0, "pps²"},      // 0: hard stop at a switch
    {22, "Bow 1", 0, kI32Max, RW, 512000, "pps³"},
    {23, "Bow 2", 0, kI32Max, RW, 512000, "pps³"},
    {24, "Bow 3", 0, kI32Max, RW, 512000, "pps³"},
    {25, "Bow 4", 0, kI32Max, RW, 512000, "pps³"},
    {26, "Virtual stop left", kI32Min, kI32Max, RW, 0, "μsteps"},
    {27, "Virtual stop right", kI32Min, kI32Max, RW, 0, "μsteps"},
    {28, "Virtual stop enable", 0, 3, RW, 0, ""},
    {29, "Virtual stop mode", 0, 2, RW, 0, ""},            // the table says R: a typo
    {35, "Bow scaling factor", 1, 255, RW, 1, ""},
    {127, "Relative positioning option", 0, 2, RW, 0, ""}, // the table says 0/1 but lists 0..2
    {131, "Measured speed", kI32Min, kI32Max, R, 0, "pps"},
    {132, "Current measured speed", kI32Min, kI32Max, R, 0, "pps"},
    {140, "Microstep resolution", 0, 8, RW, 8, ""},        // not in table (section 6.2)
    {201, "Encoder special functions", 0, 65535, RW, 0, ""},  // not in table (section 6.1)
    {202, "Motor full step resolution", 0, 65535, RW, 200, "fullsteps/round"},
    {207, "Extended error flags", 0, 2, R, 0, ""},
    {209, "Encoder position", kI32Min, kI32Max, RW, 0, "μsteps"},
    {210, "Encoder resolution", -65535, 65535, RW, 51200, ""},
    {212, "Maximum encoder deviation", 0, kI32Max, RW, 0, "encoder steps"},
    {213, "Maximum velocity deviation", 0, kI32Max, RW, 0, "pps"},  // the table says encoder steps
    {251, "Reverse shaft", 0, 1, RW, 0, ""},
    {255, "Unit mode", 0, 1, RW, 1, ""},                   // not in table (section 6.2)
};

// Table 16, plus 66, 76, 77, 84 and 85, which the text uses (SGP/GGP examples, sections 3.6.19,
// 7.4 and 7.7). Numbers 64..127 are stored in EEPROM on every SGP (section 5.1): access A.
constexpr ParamInfo kBank0[] = {
    {66, "Serial address", 1, 255, RWA, 1, ""},            // not in table
    {76, "Serial host address", 1, 255, RWA, 2, ""},       // not in table
    {77, "Auto start mode", 0, 1, RWA, 0, ""},             // not in table
    {84, "Store coordinates in EEPROM", 0, 1, RWA, 0, ""}, // not in table
    {85, "Do not restore user variables", 0, 1, RWA, 0, ""},  // not in table
    {86, "Step pulse length", 0, 255, RWA, 32, "1/16 µs"},  // unit from the text: 32 = 2 µs
    {128, "TMCL application status", 0, 3, R, 0, ""},
    {129, "Download mode", 0, 1, R, 0, ""},
    {130, "TMCL program counter", 0, 576, R, 0, ""},
    {132, "TMCL tick timer", 0, kI32Max, RW, 0, "ms"},  // unit from the text
    {133, "Random number", 0, kI32Max, RW, 0, ""},
    {255, "Suppress reply", 0, 1, RW, 0, ""},
};

// Table 18: interrupt configuration. Timer periods are unsigned 32-bit values.
constexpr ParamInfo kBank3[] = {
    {0, "Timer 0 period (ms)", 0, kU32Max, RW, 0, "ms"},
    {1, "Timer 1 period (ms)", 0, kU32Max, RW, 0, "ms"},
    {2, "Timer 2 period (ms)", 0, kU32Max, RW, 0, "ms"},
    {27, "Stop left 0 trigger transition", 0, 3, RW, 0, ""},
    {28, "Stop right 0 trigger transition", 0, 3, RW, 0, ""},
};

// Table 11. TI_TIMER0 and TI_GLOBAL are the names the manual shows; the others are ours.
constexpr InterruptVector kVectors[] = {
    {0, "TI_TIMER0", "Timer 0"},
    {1, "TI_TIMER1", "Timer 1"},
    {2, "TI_TIMER2", "Timer 2"},
    {3, "TI_TARGET0", "Target position reached, axis 0"},
    {15, "TI_STALL0", "stallGuard, axis 0"},
    {21, "TI_DEVIATION0", "Deviation, axis 0"},
    {27, "TI_STOPL0", "Left stop switch, axis 0"},
    {28, "TI_STOPR0", "Right stop switch, axis 0"},
    {255, "TI_GLOBAL", "Global interrupt enable"},
};

}  // namespace

// The generic profile runs the same motion core and borrows these tables (see generic.cpp).
extern const std::span<const ParamInfo> kUsb2SdAxisParams;
extern const std::span<const ParamInfo> kUsb2SdBank0;
extern const std::span<const ParamInfo> kUsb2SdBank3;
extern const std::span<const InterruptVector> kUsb2SdVectors;
constinit const std::span<const ParamInfo> kUsb2SdAxisParams{kAxis};
constinit const std::span<const ParamInfo> kUsb2SdBank0{kBank0};
constinit const std::span<const ParamInfo> kUsb2SdBank3{kBank3};
constinit const std::span<const InterruptVector> kUsb2SdVectors{kVectors};

const Profile kUsb2Sd{
    .name = "usb-2-sd",
    .title = "USB-2-SD (firmware 1.14)",
    // Table 5 and section 3.6 (CALL 80, UF0..UF7), SIO 14 and GIO 15 (used by the interrupt
    // example of section 3.5.5.4, where SIO is misprinted "SID"), control commands of table 13
    // and 138 (section 3.6.47).
    .commands = opcodes({1,  2,  3,  4,  5,  6,  9,  10, 11, 12, 14, 15, 19, 20, 21, 22, 23, 24, 25, 26, 27,
                         28, 30, 31, 32, 33, 34, 35, 36, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 48, 49, 50,
                         51, 55, 56, 57, 64, 65, 66, 67, 68, 69, 70, 71, 80, 128, 129, 130, 131, 132, 133,
                         134, 135, 136, 137, 138, 255}),
    .any_parameter = false,
    .axis_params = kAxis,
    .bank0 = kBank0,
    .bank3 = kBank3,
    .user_vars = 256,  // user variables (section 5.3)
    .eeprom_user_vars = 56,  // the first 56 can be stored in EEPROM
    .coords = 21,  // coordinates 0..20 per motor; 0 is RAM only
    .vectors = kVectors,
    .program_memory = 577,  // "program memory for up to 577 TMCL commands" (section 1)
    .motors = 1,
    .default_motion = "tmc4361",
    .firmware = "0015V114",
};

}  // namespace tmcl::profiles
