// drive_scan.cpp - see drive_scan.h.
#include "devices/drive_scan.h"

#include <array>
#include <cctype>
#include <fstream>
#include <set>

#include "devices/mountinfo.h"

namespace ht::devices {
namespace {

const std::filesystem::path kCalibrationFile = std::filesystem::path("LKG_calibration") / "visual.json";

// File systems a USB drive carries. Only these mounts are looked into: a stat under a network or automount file
// system (nfs, cifs, autofs, sshfs) can block for minutes, and pseudo file systems never hold a panel's drive.
bool isLocalDiskFileSystem(const std::string& fsType) {
  static const std::set<std::string> kTypes = {"vfat",    "exfat",   "msdos",   "ntfs", "ntfs3",
                                               "fuseblk", "hfsplus", "ext2",    "ext3", "ext4",
                                               "xfs",     "btrfs",   "iso9660", "udf",  "fuse.exfat"};
  return kTypes.count(fsType) != 0;
}

constexpr std::size_t kMaxMountinfoBytes = 16 << 20;

// udev escapes unsafe label characters as \xNN in by-label names ("LKG\x20P" for "LKG P").
std::string decodeUdevLabel(const std::string& name) {
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (name.compare(i, 2, "\\x") == 0 && i + 3 < name.size() &&
        std::isxdigit(static_cast<unsigned char>(name[i + 2])) &&
        std::isxdigit(static_cast<unsigned char>(name[i + 3]))) {
      out.push_back(static_cast<char>(std::stoi(name.substr(i + 2, 2), nullptr, 16)));
      i += 3;
    } else {
      out.push_back(name[i]);
    }
  }
  return out;
}

std::filesystem::path canonicalOrSelf(const std::filesystem::path& p) {
  std::error_code ec;
  std::filesystem::path c = std::filesystem::weakly_canonical(p, ec);
  return ec ? p : c;
}

std::vector<UnmountedDrive> unmountedDrives(const std::filesystem::path& byLabelDir,
                                            const std::vector<MountEntry>& mounts) {
  std::set<std::filesystem::path> mountedSources;
  for (const MountEntry& m : mounts) mountedSources.insert(canonicalOrSelf(m.source));
  std::vector<UnmountedDrive> unmounted;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(byLabelDir, ec)) {
    const std::string label = decodeUdevLabel(entry.path().filename().string());
    if (label.rfind("LKG-", 0) != 0) continue;
    const std::filesystem::path device = canonicalOrSelf(entry.path());
    if (mountedSources.count(device) == 0) unmounted.push_back({label, device});
  }
  return unmounted;
}

}  // namespace

std::string readCappedFile(const std::filesystem::path& file, std::size_t maxBytes) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw DeviceError(file.string(), DeviceFault::Unreadable, "not a regular file");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw DeviceError(file.string(), DeviceFault::Unreadable, "cannot open it for reading (permissions?)");
  // In pieces: memory follows the file, never the cap (proc files report size 0, so the size cannot be asked first).
  std::string text;
  std::array<char, 16384> piece;
  while (in.read(piece.data(), piece.size()) || in.gcount() > 0) {
    text.append(piece.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > maxBytes) {
      throw DeviceError(file.string(), DeviceFault::FileTooLarge,
                        "larger than the " + std::to_string(maxBytes) + "-byte cap");
    }
  }
  if (in.bad()) throw DeviceError(file.string(), DeviceFault::Unreadable, "read error");
  return text;
}

LoadedCalibration loadCalibrationFile(const std::filesystem::path& file, std::size_t maxBytes) {
  return checkCalibrationText(readCappedFile(file, maxBytes), file.string());
}

DriveScan scanDrives(const DriveScanOptions& options) {
  DriveScan scan;
  std::string text;
  try {
    text = readCappedFile(options.mountinfo, kMaxMountinfoBytes);
  } catch (const DeviceError&) {
    return scan;  // no mount table (not Linux, or a sandbox): nothing mounted to look at
  }
  const std::vector<MountEntry> mounts = parseMountinfo(text);
  std::set<std::filesystem::path> seen;  // bind mounts list one volume several times
  for (const MountEntry& mount : mounts) {
    if (!isLocalDiskFileSystem(mount.fsType)) continue;
    const std::filesystem::path file = mount.mountPoint / kCalibrationFile;
    std::error_code ec;
    if (!std::filesystem::exists(file, ec) || !seen.insert(canonicalOrSelf(file)).second) continue;
    DriveCalibration found{file, std::nullopt, std::nullopt};
    try {
      found.calibration = loadCalibrationFile(file, options.maxFileBytes);
    } catch (const DeviceError& e) { found.error = e; }
    scan.found.push_back(std::move(found));
  }
  scan.unmounted = unmountedDrives(options.byLabelDir, mounts);
  return scan;
}

}  // namespace ht::devices
