// device_types.cpp - see device_types.h.
#include "devices/device_types.h"

#include <array>

namespace ht::devices {
namespace {

constexpr std::array kTypes = {
    DeviceType{"LKG-2K", "Gen1 8.9\"", 2560, 1600},
    DeviceType{"LKG-4K", "Gen1 15.6\"", 3840, 2160},
    DeviceType{"LKG-8K", "Gen1 8K", 7680, 4320},
    DeviceType{"LKG-P", "Portrait", 1536, 2048},
    DeviceType{"LKG-A", "Gen2 16\"", 3840, 2160},
    DeviceType{"LKG-B", "Gen2 32\"", 7680, 4320},
    DeviceType{"LKG-D", "Gen2 65\"", 7680, 4320},
    DeviceType{"LKG-E", "Go", 1440, 2560},
    DeviceType{"LKG-F", "Kiosk", 1536, 2048},
    DeviceType{"LKG-H", "Gen3 16\" portrait", 2160, 3840},
    DeviceType{"LKG-J", "Gen3 16\" landscape", 3840, 2160},
    DeviceType{"LKG-K", "Gen3 32\" portrait", 4320, 7680},
    DeviceType{"LKG-L", "Gen3 32\" landscape", 7680, 4320},
};

}  // namespace

const DeviceType* deviceTypeOfSerial(std::string_view serial) {
  const DeviceType* best = nullptr;
  for (const DeviceType& type : kTypes) {
    if (serial.starts_with(type.prefix) && (best == nullptr || type.prefix.size() > best->prefix.size())) best = &type;
  }
  return best;
}

}  // namespace ht::devices
