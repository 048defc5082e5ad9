// libusb_hid_transport.h - HidTransport over libusb (raw USB, no hidapi, no vendor service): SET_REPORT control
// transfers for feature reports, interrupt IN transfers on endpoint 0x84 for input reports. Opening claims interface
// 0, detaching the kernel HID driver first if asked; the destructor releases the interface and reattaches the driver.
#pragma once
#include <memory>
#include <string>

#include "devices/device_error.h"
#include "devices/hid_transport.h"

struct libusb_device;  // libusb.h stays out of our headers

namespace ht::devices {

class LibusbHidTransport final : public HidTransport {
 public:
  // Throws DeviceError (NoAccess, Busy, Disconnected, Transport).
  LibusbHidTransport(libusb_device* device, std::string name, bool detachKernelDriver);
  ~LibusbHidTransport() override;
  LibusbHidTransport(const LibusbHidTransport&) = delete;
  LibusbHidTransport& operator=(const LibusbHidTransport&) = delete;

  std::string name() const override { return name_; }
  void sendFeatureReport(std::span<const std::uint8_t> payload, std::chrono::milliseconds timeout) override;
  std::size_t readInput(std::span<std::uint8_t> buffer, std::chrono::milliseconds timeout) override;

 private:
  struct Handle;
  std::string name_;
  std::unique_ptr<Handle> handle_;
};

// The DeviceError for a libusb return code (LIBUSB_ERROR_*), naming `what` was being done.
DeviceError libusbError(const std::string& device, int code, const std::string& what);

}  // namespace ht::devices
