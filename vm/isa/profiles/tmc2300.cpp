// Profile of the TMC2300-MOTOR-EVAL (TMCL firmware 1.00): one battery-powered TMC2300
// StealthChop driver with a built-in stepper, reached over UART. Source: the TMC2300-MOTOR-EVAL
// TMCL firmware manual, fw 1.00, document rev 1.00. Its instruction set is the classic core only:
// no interrupts, no coordinates, none of the commands 37..80 of newer firmware. Parameters the
// manual uses in its text but leaves out of its tables are marked "not in table"; every default
// the manual does not give, and every correction of the manual, is explained in docs/profiles.md.
#include <cstdint>
#include <initializer_list>

#include "profiles.hpp"

namespace tmcl::profiles {
namespace {

constexpr std::uint8_t R = kRead;
constexpr std::uint8_t RW = kRead | kWrite;
constexpr std::uint8_t RWE = kRead | kWrite | kEeprom;
constexpr std::uint8_t RWA = kRead | kWrite | kAutoStore;

constexpr std::int64_t kI32Min = -2147483648LL;
constexpr std::int64_t kI32Max = 2147483647LL;

// Table 11. The access column has no E although STAP/RSAP exist; settings get E, state does not.
constexpr ParamInfo kAxis[] = {
    {0, "Target position", kI32Min, kI32Max, RW, 0, "μsteps"},
    {1, "Actual position", kI32Min, kI32Max, RW, 0, "μsteps"},
    {2, "Target speed", -32768, 32767, RW, 0, "pps"},
    {3, "Actual speed", -32768, 32767, R, 0, "pps"},
    {4, "Maximum positioning speed", 0, 32767, RWE, 10000, "pps"},
    {5, "Maximum acceleration", 0, kI32Max, RWE, 10000, "pps²"},
    {6, "Maximum current", 0, 31, RWE, 16, ""},
    {7, "Standby current", 0, 31, RWE, 8, ""},
    {8, "Position reached flag", 0, 1, R, 1, ""},
    {29, "Measured speed", 0, 7999774, R, 0, "pps"},
    {100, "Step generator", kI32Min, kI32Max, RW, 0, "pps"},  // unit from the text
    {140, "Microstep resolution", 0, 8, RWE, 8, ""},
    {141, "Microstep interpolation enable", 0, 1, RWE, 1, ""},
    {162, "Chopper blank time", 0, 3, RWE, 2, ""},
    {168, "SmartEnergy current minimum (SEIMIN)", 0, 1, RWE, 0, ""},
    {169, "SmartEnergy current down step", 0, 3, RWE, 0, ""},
    {170, "SmartEnergy hysteresis", 0, 15, RWE, 0, ""},
    {171, "SmartEnergy current up step", 0, 3, RWE, 0, ""},
    {172, "SmartEnergy hysteresis start", 0, 15, RWE, 0, ""},
    {174, "StallGuard2 threshold", 0, 255, RWE, 0, ""},
    {180, "SmartEnergy actual current", 0, 31, R, 0, ""},
    {181, "Stop on stall", 0, kI32Max, RWE, 0, "pps"},
    {182, "SmartEnergy threshold speed", 0, 1048574, RWE, 0, "pps"},
    {187, "PWM gradient", 0, 15, RWE, 1, ""},
    {191, "PWM frequency", 0, 3, RWE, 1, ""},
    {192, "PWM autoscale", 0, 1, RWE, 1, ""},
    {204, "Freewheeling mode", 0, 3, RWE, 0, ""},
    {206, "Actual load value", 0, 1023, R, 0, ""},
    {220, "Supply voltage", 0, 51, R, 37, "0.1 V"},  // the table says RW (a measurement) and 1/10V
};

// Table 13, plus 66 (the SGP/GGP examples) and 85 (section 6.4).
constexpr ParamInfo kBank0[] = {
    {65, "UART baud rate", 0, 7, RWA, 0, ""},
    {66, "Serial address", 1, 255, RWA, 1, ""},                // not in table
    {77, "Auto start mode", 0, 1, RWA, 0, ""},
    {85, "Do not restore user variables", 0, 1, RWA, 0, ""},   // not in table
    {128, "TMCL application status", 0, 3, R, 0, ""},
    {130, "TMCL program counter", 0, 2047, R, 0, ""},
    {132, "TMCL tick timer", 0, kI32Max, RW, 0, "ms"},  // unit from the text
};

std::bitset<256> opcodes(std::initializer_list<int> codes) {
  std::bitset<256> b;
  for (int c : codes) b.set(static_cast<std::size_t>(c));
  return b;
}

}  // namespace

const Profile kTmc2300Eval{
    .name = "tmc2300-eval",
    .title = "TMC2300-MOTOR-EVAL (firmware 1.00)",
    // Table 5, UF0..UF7 (section 3.6.25), SIO 14 and GIO 15 (the first example program uses
    // SIO, the AAP example GIO) and the control commands of table 10 (no 138).
    .commands = opcodes({1,  2,  3,  4,  5,  6,  7,  8,  9,  10, 11, 12, 14, 15, 19, 20, 21, 22, 23, 24, 27,
                         28, 33, 34, 35, 36, 64, 65, 66, 67, 68, 69, 70, 71, 128, 129, 130, 131, 132, 133,
                         134, 135, 136, 137, 255}),
    .any_parameter = false,
    .axis_params = kAxis,
    .bank0 = kBank0,
    .bank3 = {},  // no bank 3: the module has no interrupts
    .user_vars = 256,  // user variables (section 5.2 text)
    .eeprom_user_vars = 8,  // table 14 marks only 0..7 E
    .coords = 0,  // no SCO/GCO/CCO/ACO, so MVP COORD has nothing to move to
    .vectors = {},  // no interrupt vectors
    .program_memory = 2048,  // the manual gives no size; 2048 words as in current TMCL firmware
    .motors = 1,
    .default_motion = "linear",
    .firmware = "2300V100",
};

}  // namespace tmcl::profiles
