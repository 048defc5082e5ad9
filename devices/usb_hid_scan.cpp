// usb_hid_scan.cpp - see usb_hid_scan.h.
#include "devices/usb_hid_scan.h"

#include <libusb.h>

#include <cstdio>
#include <fstream>
#include <memory>

#include "devices/gen1_protocol.h"
#include "devices/libusb_hid_transport.h"

namespace ht::devices {
namespace {

struct ContextDeleter {
  void operator()(libusb_context* c) const { libusb_exit(c); }
};
struct DeviceListDeleter {
  void operator()(libusb_device** list) const { libusb_free_device_list(list, 1); }
};

// "1-1.4": the device's name under /sys/bus/usb/devices (bus, then the port path).
std::string sysfsName(libusb_device* device) {
  std::uint8_t ports[8];
  const int depth = libusb_get_port_numbers(device, ports, sizeof ports);
  std::string name = std::to_string(libusb_get_bus_number(device));
  for (int i = 0; i < depth; ++i) name += (i == 0 ? "-" : ".") + std::to_string(ports[i]);
  return name;
}

// The product string from sysfs (no control transfer needed); empty when unknown.
std::string sysfsProduct(libusb_device* device) {
  std::ifstream in("/sys/bus/usb/devices/" + sysfsName(device) + "/product");
  std::string product;
  std::getline(in, product);
  return product;
}

std::string deviceName(libusb_device* device, const std::string& product) {
  char text[64];
  std::snprintf(text, sizeof text, "USB %03u/%03u %04x:%04x", libusb_get_bus_number(device),
                libusb_get_device_address(device), gen1::kVendorId, gen1::kProductId);
  return std::string(text) + (product.empty() ? "" : " " + product);
}

// VID 04d8 is Microchip's: a known product string other than "HoloPlay" is another device.
bool isHoloPlay(libusb_device* device, std::string& product) {
  libusb_device_descriptor descriptor{};
  if (libusb_get_device_descriptor(device, &descriptor) != 0) return false;
  if (descriptor.idVendor != gen1::kVendorId || descriptor.idProduct != gen1::kProductId) return false;
  product = sysfsProduct(device);
  return product.empty() || product == gen1::kProductName;
}

UsbHidResult readDevice(libusb_device* device, const std::string& name, const UsbScanOptions& options) {
  UsbHidResult result{name, std::nullopt, std::nullopt};
  try {
    LibusbHidTransport transport(device, name, options.detachKernelDriver);
    result.calibration = readGen1Calibration(transport, options.read);
  } catch (const DeviceError& e) { result.error = e; }
  return result;
}

}  // namespace

UsbScan scanUsbHid(const UsbScanOptions& options) {
  UsbScan scan;
  libusb_context* raw = nullptr;
  if (int rc = libusb_init(&raw); rc != 0) {
    scan.unavailable = std::string("libusb_init: ") + libusb_error_name(rc) + " (no /dev/bus/usb here?)";
    return scan;
  }
  std::unique_ptr<libusb_context, ContextDeleter> context(raw);
  libusb_device** rawList = nullptr;
  const ssize_t count = libusb_get_device_list(context.get(), &rawList);
  if (count < 0) {
    scan.unavailable = std::string("libusb_get_device_list: ") + libusb_error_name(static_cast<int>(count));
    return scan;
  }
  std::unique_ptr<libusb_device*, DeviceListDeleter> list(rawList);
  for (ssize_t i = 0; i < count; ++i) {
    std::string product;
    if (!isHoloPlay(rawList[i], product)) continue;
    scan.devices.push_back(readDevice(rawList[i], deviceName(rawList[i], product), options));
  }
  return scan;
}

}  // namespace ht::devices
