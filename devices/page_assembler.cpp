// page_assembler.cpp - see page_assembler.h.
#include "devices/page_assembler.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "devices/device_error.h"

namespace ht::devices {
namespace {

// The largest JSON the 16-bit page number can address.
constexpr std::size_t kAddressableJsonBytes =
    (std::size_t{std::numeric_limits<std::uint16_t>::max()} + 1) * gen1::kPageBytes - gen1::kLengthPrefixBytes;

std::uint32_t bigEndian32(std::span<const std::uint8_t, gen1::kPageBytes> data) {
  return (std::uint32_t{data[0]} << 24) | (std::uint32_t{data[1]} << 16) | (std::uint32_t{data[2]} << 8) |
         std::uint32_t{data[3]};
}

}  // namespace

PageAssembler::PageAssembler(std::string device, std::size_t maxJsonBytes)
    : device_(std::move(device)), maxJsonBytes_(std::min(maxJsonBytes, kAddressableJsonBytes)) {}

std::size_t PageAssembler::pagesNeeded() const {
  return (kHeader + jsonBytes_ + gen1::kPageBytes - 1) / gen1::kPageBytes;
}

void PageAssembler::addPage(std::span<const std::uint8_t, gen1::kPageBytes> data) {
  if (complete()) throw std::logic_error("PageAssembler::addPage after the calibration was complete");
  if (pagesRead_ == 0) {
    const std::uint32_t length = bigEndian32(data);
    if (length == 0 || length == gen1::kNoCalibration) {
      throw DeviceError(device_, DeviceFault::EmptyCalibration,
                        "the EEPROM holds no calibration (length prefix " + std::to_string(length) +
                            "); the panel needs its factory calibration written back");
    }
    if (length > maxJsonBytes_) {
      throw DeviceError(device_, DeviceFault::LengthOverCap,
                        "the length prefix announces " + std::to_string(length) + " bytes of JSON, more than the " +
                            std::to_string(maxJsonBytes_) + "-byte cap (a corrupt EEPROM or not a Looking Glass)");
    }
    jsonBytes_ = length;
    bytes_.reserve(pagesNeeded() * gen1::kPageBytes);
  }
  bytes_.append(reinterpret_cast<const char*>(data.data()), data.size());
  ++pagesRead_;
}

std::string PageAssembler::takeJson() {
  if (!complete()) throw std::logic_error("PageAssembler::takeJson before the calibration was complete");
  std::string json = bytes_.substr(kHeader, jsonBytes_);
  bytes_.clear();
  return json;
}

}  // namespace ht::devices
