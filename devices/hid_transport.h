// hid_transport.h - the two HID operations the Gen1 calibration reader needs, behind an interface so the protocol
// code runs against libusb (libusb_hid_transport.h) or an in-memory fake (tests/devices/fake_holoplay.h).
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace ht::devices {

class HidTransport {
 public:
  virtual ~HidTransport() = default;

  // Names the device in errors, e.g. "USB 001/002 04d8:ef7e HoloPlay".
  virtual std::string name() const = 0;

  // Sends a feature report with report id 0: `payload` is the report without the id byte. Throws DeviceError.
  virtual void sendFeatureReport(std::span<const std::uint8_t> payload, std::chrono::milliseconds timeout) = 0;

  // Reads up to `buffer.size()` bytes of input report data; returns how many arrived (>= 1). A report may arrive in
  // parts (64 + 4 bytes over libusb): the caller loops. Throws DeviceError (Timeout when nothing arrived in time).
  virtual std::size_t readInput(std::span<std::uint8_t> buffer, std::chrono::milliseconds timeout) = 0;
};

}  // namespace ht::devices
