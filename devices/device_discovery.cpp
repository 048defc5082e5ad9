// device_discovery.cpp - see device_discovery.h.
#include "devices/device_discovery.h"

#include <set>

#include "devices/device_types.h"

namespace ht::devices {
namespace {

FoundDevice makeFound(CalibrationSource source, std::string location, std::optional<LoadedCalibration> calibration,
                      std::optional<DeviceError> error) {
  FoundDevice found{source, std::move(location), "", "", std::move(calibration), std::move(error), "", ""};
  if (found.calibration) {
    found.serial = found.calibration->calibration.serial;
    if (const DeviceType* type = deviceTypeOfSerial(found.serial)) found.deviceType = std::string(type->name);
  }
  return found;
}

class DeviceList {
 public:
  explicit DeviceList(Discovery& out) : out_(out) {}

  // Adds the device unless a source earlier in the order already gave its serial.
  void add(FoundDevice found) {
    if (!found.serial.empty() && !serials_.insert(found.serial).second) {
      out_.notes.push_back(found.serial + " at " + found.location + " (" +
                           std::string(calibrationSourceName(found.source)) +
                           ") left out: an earlier source already gave this serial");
      return;
    }
    out_.devices.push_back(std::move(found));
  }

 private:
  Discovery& out_;
  std::set<std::string> serials_;
};

void addConfigFile(const DiscoveryOptions& options, DeviceList& list) {
  if (options.calibrationFile.empty()) return;
  std::optional<LoadedCalibration> calibration;
  std::optional<DeviceError> error;
  try {
    calibration = loadCalibrationFile(options.calibrationFile, options.drives.maxFileBytes);
  } catch (const DeviceError& e) { error = e; }
  list.add(makeFound(CalibrationSource::ConfigFile, options.calibrationFile.string(), std::move(calibration),
                     std::move(error)));
}

void addDrives(const DiscoveryOptions& options, DeviceList& list) {
  if (!options.scanDrives) return;
  DriveScan scan = scanDrives(options.drives);
  for (DriveCalibration& d : scan.found) {
    list.add(makeFound(CalibrationSource::MountedDrive, d.file.string(), std::move(d.calibration), std::move(d.error)));
  }
  for (const UnmountedDrive& d : scan.unmounted) {
    FoundDevice found = makeFound(CalibrationSource::DriveNotMounted, d.label + " (" + d.device.string() + ")",
                                  std::nullopt, std::nullopt);
    found.serial = d.label;  // the volume label is the serial
    if (const DeviceType* type = deviceTypeOfSerial(d.label)) found.deviceType = std::string(type->name);
    list.add(std::move(found));
  }
}

void addUsb(const DiscoveryOptions& options, Discovery& out, DeviceList& list) {
  if (!options.scanUsb) return;
  UsbScan scan = options.usbScanner ? options.usbScanner(options.usb) : scanUsbHid(options.usb);
  if (!scan.unavailable.empty()) out.notes.push_back("USB not scanned: " + scan.unavailable);
  for (UsbHidResult& r : scan.devices) {
    list.add(makeFound(CalibrationSource::UsbHid, r.device, std::move(r.calibration), std::move(r.error)));
  }
}

}  // namespace

std::string_view calibrationSourceName(CalibrationSource source) {
  switch (source) {
    case CalibrationSource::ConfigFile: return "config-file";
    case CalibrationSource::MountedDrive: return "mounted-drive";
    case CalibrationSource::UsbHid: return "usb-hid";
    case CalibrationSource::DriveNotMounted: return "drive-not-mounted";
  }
  return "unknown";
}

std::string FoundDevice::problem() const {
  if (error) return error->what();
  if (source == CalibrationSource::DriveNotMounted) return "plugged in but not mounted: mount " + location;
  return "";
}

Discovery discoverDevices(const DiscoveryOptions& options) {
  Discovery out;
  DeviceList list(out);
  addConfigFile(options, list);
  addDrives(options, list);
  addUsb(options, out, list);
  if (options.matchMonitor) {
    for (FoundDevice& device : out.devices) {
      if (!device.loaded()) continue;
      MonitorMatch match = options.matchMonitor(device);
      device.matchedMonitor = std::move(match.monitor);
      device.monitorProblem = std::move(match.problem);
    }
  }
  return out;
}

}  // namespace ht::devices
