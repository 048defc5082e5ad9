// usb_hid_scan.h - finds Gen1 Looking Glass panels on USB with libusb and reads each one's calibration over HID
// (gen1_calibration_reader.h). libusb stays inside usb_hid_scan.cpp / libusb_hid_transport.cpp: callers never see it.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "devices/device_error.h"
#include "devices/gen1_calibration_reader.h"

namespace ht::devices {

struct UsbScanOptions {
  // Detach the kernel's HID driver from the interface when it holds it (reattached afterwards). Off: a bound driver
  // makes the read fail with DeviceFault::Busy. umockdev cannot emulate the detach (docs/DISPLAY.md).
  bool detachKernelDriver = true;
  HidReadOptions read;
};

// One Gen1 panel seen on USB: either its calibration or the error that kept it from loading.
struct UsbHidResult {
  std::string device;  // "USB 001/002 04d8:ef7e HoloPlay"
  std::optional<LoadedCalibration> calibration;
  std::optional<DeviceError> error;
};

struct UsbScan {
  std::vector<UsbHidResult> devices;
  std::string unavailable;  // why USB could not be scanned at all (no /dev/bus/usb, ...); empty when it could
};

UsbScan scanUsbHid(const UsbScanOptions& options);

}  // namespace ht::devices
