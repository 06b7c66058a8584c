// Names for the axis and global parameter numbers the code itself needs (the manuals' numbers
// and names, USB-2-SD section 6 and TMC2300-MOTOR-EVAL section 5), so that no file writes a bare
// 4 or 84, and for the status codes of a module's replies. Only the names live here: a
// parameter's range, default and access come from the module's profile (profile.hpp) and
// nowhere else.
#pragma once

#include <cstdint>

namespace tmcl {

// Axis parameters (SAP, GAP, AAP, STAP, RSAP).
enum AxisParam : std::uint8_t {
  kApTargetPosition = 0,
  kApActualPosition = 1,
  kApTargetSpeed = 2,
  kApActualSpeed = 3,
  kApMaxPositioningSpeed = 4,
  kApMaxAcceleration = 5,
  kApRunCurrent = 6,
  kApStandbyCurrent = 7,
  kApPositionReached = 8,
  kApRampType = 14,
  kApStartVelocity = 15,
  kApStartAcceleration = 16,
  kApMaxDeceleration = 17,
  kApBreakVelocity = 18,
  kApFinalDeceleration = 19,
  kApStopVelocity = 20,
  kApStopDeceleration = 21,
  kApBow1 = 22,
  kApBow2 = 23,
  kApBow3 = 24,
  kApBow4 = 25,
  kApVirtualStopLeft = 26,
  kApVirtualStopRight = 27,
  kApVirtualStopEnable = 28,
  kApVirtualStopMode = 29,  // USB-2-SD; the TMC2300-MOTOR-EVAL's 29 is its measured speed
  kApBowScalingFactor = 35,
  kApRelativePositioningOption = 127,
  kApMeasuredSpeed = 131,
  kApCurrentMeasuredSpeed = 132,
  kApMicrostepResolution = 140,
  kApMicrostepInterpolation = 141,
  kApSmartEnergyActualCurrent = 180,
  kApFullStepResolution = 202,
  kApExtendedErrorFlags = 207,
  kApEncoderPosition = 209,
  kApEncoderResolution = 210,
  kApMaxEncoderDeviation = 212,
  kApReverseShaft = 251,
  kApUnitMode = 255,
};

// Global parameters of bank 0 (SGP, GGP, AGP, STGP, RSGP).
enum GlobalParam : std::uint8_t {
  kGpSerialAddress = 66,
  kGpSerialHostAddress = 76,
  kGpAutoStart = 77,
  kGpCoordinatesInEeprom = 84,
  kGpDoNotRestoreUserVars = 85,
  kGpApplicationStatus = 128,
  kGpDownloadMode = 129,
  kGpProgramCounter = 130,
  kGpTickTimer = 132,
  kGpRandomNumber = 133,
  kGpSuppressReply = 255,
};

// Status codes of a reply (the manuals' table of reply status, TMCL host protocol).
inline constexpr std::uint8_t kStatusWrongChecksum = 1, kStatusInvalidCommand = 2, kStatusWrongType = 3,
                              kStatusInvalidValue = 4, kStatusEepromLocked = 5, kStatusNotAvailable = 6,
                              kStatusOk = 100, kStatusLoaded = 101, kStatusPositionReached = 128;

}  // namespace tmcl
