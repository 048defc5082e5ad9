// device_types.h - the Looking Glass device type named by a calibration serial's prefix ("LKG-P00671" -> Portrait),
// with the panel size that type has (docs/DISPLAY.md "Calibration from the device", table and sources).
#pragma once
#include <cstdint>
#include <string_view>

namespace ht::devices {

struct DeviceType {
  std::string_view prefix;  // "LKG-P"
  std::string_view name;    // "Portrait"
  std::uint32_t screenW = 0, screenH = 0;
};

// The type whose prefix the serial starts with (longest prefix wins); nullptr when none does.
const DeviceType* deviceTypeOfSerial(std::string_view serial);

}  // namespace ht::devices
