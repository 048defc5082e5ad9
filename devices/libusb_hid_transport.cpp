// libusb_hid_transport.cpp - see libusb_hid_transport.h.
#include "devices/libusb_hid_transport.h"

#include <libusb.h>

#include <algorithm>
#include <vector>

#include "devices/device_error.h"
#include "devices/gen1_protocol.h"

namespace ht::devices {
namespace {

constexpr std::uint8_t kClassInterfaceOut = 0x21;    // bmRequestType: host to device, class, interface
constexpr std::uint8_t kSetReport = 0x09;            // HID SET_REPORT
constexpr std::uint16_t kFeatureReportId0 = 0x0300;  // wValue: report type 3 (feature) << 8 | report id 0

unsigned int timeoutMs(std::chrono::milliseconds timeout) {
  // libusb treats 0 as "wait forever": never pass it.
  return static_cast<unsigned int>(std::max<std::chrono::milliseconds::rep>(1, timeout.count()));
}

}  // namespace

DeviceError libusbError(const std::string& device, int code, const std::string& what) {
  const std::string detail = what + ": " + libusb_error_name(code);
  switch (code) {
    case LIBUSB_ERROR_ACCESS:
      return {device, DeviceFault::NoAccess,
              detail + " (install configs/udev/70-holotrace-lkg.rules and replug, see docs/DISPLAY.md)"};
    case LIBUSB_ERROR_BUSY:
      return {device, DeviceFault::Busy,
              detail + " (another program or the kernel's HID driver holds the interface; allow detaching it)"};
    case LIBUSB_ERROR_TIMEOUT: return {device, DeviceFault::Timeout, detail};
    case LIBUSB_ERROR_PIPE: return {device, DeviceFault::Stall, detail + " (the device stalled the endpoint)"};
    case LIBUSB_ERROR_NO_DEVICE: return {device, DeviceFault::Disconnected, detail + " (the device was unplugged)"};
    default: return {device, DeviceFault::Transport, detail};
  }
}

struct LibusbHidTransport::Handle {
  libusb_device_handle* usb = nullptr;
  bool claimed = false;
  bool detached = false;

  ~Handle() {
    if (usb == nullptr) return;
    if (claimed) libusb_release_interface(usb, gen1::kInterface);
    if (detached) libusb_attach_kernel_driver(usb, gen1::kInterface);
    libusb_close(usb);
  }
};

LibusbHidTransport::LibusbHidTransport(libusb_device* device, std::string name, bool detachKernelDriver)
    : name_(std::move(name)), handle_(std::make_unique<Handle>()) {
  if (int rc = libusb_open(device, &handle_->usb); rc != 0) {
    handle_->usb = nullptr;
    throw libusbError(name_, rc, "opening the device");
  }
  // Detach by hand, only when a driver is bound: libusb's auto-detach uses USBDEVFS_DISCONNECT_CLAIM, which fails
  // where that ioctl is not available (umockdev).
  if (detachKernelDriver && libusb_kernel_driver_active(handle_->usb, gen1::kInterface) == 1) {
    if (int rc = libusb_detach_kernel_driver(handle_->usb, gen1::kInterface); rc != 0) {
      throw libusbError(name_, rc, "detaching the kernel HID driver from interface 0");
    }
    handle_->detached = true;
  }
  if (int rc = libusb_claim_interface(handle_->usb, gen1::kInterface); rc != 0) {
    throw libusbError(name_, rc, "claiming interface 0");
  }
  handle_->claimed = true;
}

LibusbHidTransport::~LibusbHidTransport() = default;

void LibusbHidTransport::sendFeatureReport(std::span<const std::uint8_t> payload, std::chrono::milliseconds timeout) {
  std::vector<unsigned char> data(payload.begin(), payload.end());  // libusb wants a mutable buffer
  const int rc =
      libusb_control_transfer(handle_->usb, kClassInterfaceOut, kSetReport, kFeatureReportId0, gen1::kInterface,
                              data.data(), static_cast<std::uint16_t>(data.size()), timeoutMs(timeout));
  if (rc < 0) throw libusbError(name_, rc, "sending the read request (SET_REPORT)");
  if (static_cast<std::size_t>(rc) != data.size()) {
    throw DeviceError(
        name_, DeviceFault::Transport,
        "the device took " + std::to_string(rc) + " of " + std::to_string(data.size()) + " bytes of the read request");
  }
}

std::size_t LibusbHidTransport::readInput(std::span<std::uint8_t> buffer, std::chrono::milliseconds timeout) {
  int transferred = 0;
  const int rc = libusb_interrupt_transfer(handle_->usb, gen1::kInputEndpoint, buffer.data(),
                                           static_cast<int>(buffer.size()), &transferred, timeoutMs(timeout));
  if (rc == LIBUSB_ERROR_TIMEOUT && transferred > 0) return static_cast<std::size_t>(transferred);
  if (rc != 0) throw libusbError(name_, rc, "reading the reply from endpoint 0x84");
  return static_cast<std::size_t>(transferred);
}

}  // namespace ht::devices
