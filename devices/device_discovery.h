// device_discovery.h - every Looking Glass panel this host can see, in the order their calibration is trusted:
// an explicit calibration file, then visual.json on a mounted drive, then the Gen1 EEPROM over USB HID. A serial
// already found from an earlier source is not listed again. Used by `holotrace devices` and holotraced.
#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "devices/device_error.h"
#include "devices/drive_scan.h"
#include "devices/loaded_calibration.h"
#include "devices/usb_hid_scan.h"

namespace ht::devices {

enum class CalibrationSource { ConfigFile, MountedDrive, UsbHid, DriveNotMounted };
// "config-file" | "mounted-drive" | "usb-hid" | "drive-not-mounted"
std::string_view calibrationSourceName(CalibrationSource source);

struct FoundDevice {
  CalibrationSource source = CalibrationSource::ConfigFile;
  std::string location;    // the file, "USB 001/002 04d8:ef7e HoloPlay", or the drive label and device
  std::string serial;      // from the calibration; empty when it could not be read
  std::string deviceType;  // from the serial prefix (device_types.h); empty when unknown
  std::optional<LoadedCalibration> calibration;  // set exactly when everything loaded and validated
  std::optional<DeviceError> error;              // why it did not load
  // The monitor showing this panel, from DiscoveryOptions::matchMonitor; `holotrace devices` prints "-" while empty.
  std::string matchedMonitor;
  // Why no monitor was matched (no X server, no monitor of the panel's size, ambiguity, ...); "" when matched or
  // when no matching was asked for. Not a device error: the calibration loaded all the same.
  std::string monitorProblem;

  bool loaded() const { return calibration.has_value(); }
  std::string problem() const;  // the error text, "plugged in but not mounted", or ""
};

// What DiscoveryOptions::matchMonitor says about one panel: the monitor's name, or why there is none.
struct MonitorMatch {
  std::string monitor;
  std::string problem;
};

struct DiscoveryOptions {
  std::filesystem::path calibrationFile;  // explicit visual.json; empty = none
  bool scanDrives = true;
  DriveScanOptions drives;
  bool scanUsb = true;
  UsbScanOptions usb;
  // Replaces the libusb scan (tests); unset = scanUsbHid(usb).
  std::function<UsbScan(const UsbScanOptions&)> usbScanner;
  // Hook for the display sink's monitor picker (RandR monitor by EDID name / panel size / configuration): called for
  // every panel that loaded. `holotrace devices` plugs in present::MonitorLookup; unset = no monitor matching.
  std::function<MonitorMatch(const FoundDevice&)> matchMonitor;
};

struct Discovery {
  std::vector<FoundDevice> devices;
  std::vector<std::string> notes;  // sources that could not be scanned, duplicates left out
};

Discovery discoverDevices(const DiscoveryOptions& options);

}  // namespace ht::devices
