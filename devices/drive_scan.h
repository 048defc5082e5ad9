// drive_scan.h - finds Looking Glass calibration on mounted drives (Portrait and later panels carry
// LKG_calibration/visual.json on a USB mass-storage volume labelled like the serial) and reports panels whose volume
// is plugged in but not mounted (/dev/disk/by-label/LKG-*). Both roots are injectable for tests.
#pragma once
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "devices/device_error.h"
#include "devices/loaded_calibration.h"

namespace ht::devices {

struct DriveScanOptions {
  std::filesystem::path mountinfo = "/proc/self/mountinfo";
  std::filesystem::path byLabelDir = "/dev/disk/by-label";
  std::size_t maxFileBytes = 1 << 20;  // visual.json is ~1 KiB; anything near this is not one
};

struct DriveCalibration {
  std::filesystem::path file;  // <mount point>/LKG_calibration/visual.json
  std::optional<LoadedCalibration> calibration;
  std::optional<DeviceError> error;
};

struct UnmountedDrive {
  std::string label;             // "LKG-P00671"
  std::filesystem::path device;  // what the label link points to, e.g. /dev/sdb1
};

struct DriveScan {
  std::vector<DriveCalibration> found;
  std::vector<UnmountedDrive> unmounted;
};

DriveScan scanDrives(const DriveScanOptions& options);

// Reads `file` if it is a regular file of at most `maxBytes` bytes (never reading more); throws DeviceError
// (FileTooLarge, Unreadable) naming the file.
std::string readCappedFile(const std::filesystem::path& file, std::size_t maxBytes);

// Loads and validates one visual.json (config file or drive); throws DeviceError.
LoadedCalibration loadCalibrationFile(const std::filesystem::path& file, std::size_t maxBytes);

}  // namespace ht::devices
