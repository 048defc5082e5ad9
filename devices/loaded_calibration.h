// loaded_calibration.h - a device's calibration text checked end to end: valid JSON, a JSON object, and a visual.json
// that passes camera_models' validation. Every source (config file, drive, USB HID) goes through this one gate, so a
// device is either fully loaded or not at all.
#pragma once
#include <string>

#include "camera_models/looking_glass_calibration.h"

namespace ht::devices {

struct LoadedCalibration {
  std::string json;                     // the bytes as the device holds them
  LookingGlassCalibration calibration;  // parsed and validated
};

// Throws DeviceError (InvalidJson, InvalidCalibration) naming `device`.
LoadedCalibration checkCalibrationText(std::string json, const std::string& device);

}  // namespace ht::devices
