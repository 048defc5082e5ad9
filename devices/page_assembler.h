// page_assembler.h - reassembles the Gen1 calibration from its EEPROM pages (gen1_protocol.h): decodes and caps the
// length prefix on page 0, appends each page's data and knows which page comes next and when the JSON is complete.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "devices/gen1_protocol.h"

namespace ht::devices {

class PageAssembler {
 public:
  // `device` names the device in errors; a length prefix above `maxJsonBytes` is refused before anything is stored.
  PageAssembler(std::string device, std::size_t maxJsonBytes);

  // Appends the data of page nextPage(). Throws DeviceError (LengthOverCap, EmptyCalibration) on page 0.
  void addPage(std::span<const std::uint8_t, gen1::kPageBytes> data);

  std::uint16_t nextPage() const { return pagesRead_; }
  bool complete() const { return pagesRead_ > 0 && bytes_.size() >= kHeader + jsonBytes_; }
  std::size_t jsonBytes() const { return jsonBytes_; }  // valid after page 0
  std::size_t pagesNeeded() const;                      // valid after page 0
  std::string takeJson();                               // the JSON text, once complete()

 private:
  static constexpr std::size_t kHeader = gen1::kLengthPrefixBytes;
  std::string device_;
  std::size_t maxJsonBytes_;
  std::size_t jsonBytes_ = 0;
  std::uint16_t pagesRead_ = 0;
  std::string bytes_;  // length prefix + JSON so far
};

}  // namespace ht::devices
