// device_error.h - the error of everything that reads calibration from a display device (USB HID, a mounted drive).
// what(): "<device>: <fault>: <detail>". Callers branch on fault(), never on the text. A DeviceError means nothing
// of that device was loaded (docs/DISPLAY.md "Calibration from the device").
#pragma once
#include <string>
#include <string_view>

#include "common/error.h"

namespace ht::devices {

enum class DeviceFault {
  NoAccess,            // permission denied opening the device (udev rule missing)
  Busy,                // another driver or program holds the interface
  Transport,           // any other USB / I/O failure
  Timeout,             // the device did not answer in time
  Stall,               // the device stalled an endpoint (USB STALL handshake)
  Disconnected,        // the device went away while being read
  TruncatedReport,     // an input report stopped short and the rest never came
  EchoMismatch,        // the device kept answering for another page than the one asked for
  LengthOverCap,       // the length prefix announces more bytes than the reader accepts
  EmptyCalibration,    // the EEPROM holds no calibration (length 0 or 0xffffffff)
  InvalidJson,         // the calibration bytes are not a JSON object
  InvalidCalibration,  // valid JSON that fails visual.json validation
  FileTooLarge,        // visual.json on a drive is larger than the cap
  Unreadable,          // visual.json on a drive cannot be read
};

// Stable lowercase name of a fault ("echo-mismatch"), used in messages and `holotrace devices --json`.
std::string_view deviceFaultName(DeviceFault fault);

class DeviceError : public Error {
 public:
  DeviceError(std::string device, DeviceFault fault, const std::string& detail)
      : Error(device + ": " + std::string(deviceFaultName(fault)) + ": " + detail),
        device_(std::move(device)),
        fault_(fault),
        detail_(detail) {}
  const std::string& device() const { return device_; }
  DeviceFault fault() const { return fault_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string device_;
  DeviceFault fault_;
  std::string detail_;
};

}  // namespace ht::devices
