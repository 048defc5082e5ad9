// loaded_calibration.cpp - see loaded_calibration.h.
#include "devices/loaded_calibration.h"

#include <nlohmann/json.hpp>

#include "devices/device_error.h"

namespace ht::devices {

LoadedCalibration checkCalibrationText(std::string json, const std::string& device) {
  // nlohmann/json stops at a NUL byte as if the text ended there: a length prefix longer than the JSON (padding of
  // zero bytes) would pass unnoticed.
  if (const std::size_t nul = json.find('\0'); nul != std::string::npos) {
    throw DeviceError(device, DeviceFault::InvalidJson,
                      "the calibration (" + std::to_string(json.size()) + " bytes) holds a NUL byte at offset " +
                          std::to_string(nul) + " (its length prefix does not match the JSON)");
  }
  nlohmann::json parsed;
  try {
    parsed = nlohmann::json::parse(json);
  } catch (const nlohmann::json::exception& e) {
    throw DeviceError(device, DeviceFault::InvalidJson,
                      "the calibration (" + std::to_string(json.size()) + " bytes) is not valid JSON: " + e.what());
  }
  if (!parsed.is_object()) {
    throw DeviceError(device, DeviceFault::InvalidJson,
                      std::string("the calibration is JSON but not an object (a ") + parsed.type_name() + ")");
  }
  try {
    LookingGlassCalibration calibration = parseLookingGlassCalibration(parsed, device);
    return {std::move(json), std::move(calibration)};
  } catch (const ConfigError& e) {
    throw DeviceError(device, DeviceFault::InvalidCalibration,
                      "field '" + e.field() + "' = " + e.value() + ": " + e.expected());
  }
}

}  // namespace ht::devices
