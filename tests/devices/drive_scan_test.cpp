// drive_scan_test.cpp - the mountinfo parser, the drive scan (visual.json on mounted volumes, "plugged in but not
// mounted" from by-label links) on injected roots, and the source order of device discovery.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "devices/device_discovery.h"
#include "devices/device_types.h"
#include "devices/mountinfo.h"
#include "tests/common/temp_directory.h"

namespace ht::devices {
namespace {

namespace fs = std::filesystem;

std::string fixtureText(const std::string& name) {
  std::ifstream in(std::string(HT_TEST_DATA_DIR) + "/configs/" + name, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeFile(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
}

// The mountinfo form of a path: space, tab, newline and backslash as octal escapes.
std::string escapeMountPath(const std::string& path) {
  std::string out;
  for (char c : path) {
    if (c == ' ')
      out += "\\040";
    else if (c == '\t')
      out += "\\011";
    else if (c == '\n')
      out += "\\012";
    else if (c == '\\')
      out += "\\134";
    else
      out += c;
  }
  return out;
}

std::string mountLine(int id, const fs::path& mountPoint, const std::string& source,
                      const std::string& fsType = "vfat") {
  return std::to_string(id) + " 1 8:" + std::to_string(id) + " / " + escapeMountPath(mountPoint.string()) +
         " rw,nosuid,nodev,relatime shared:" + std::to_string(id) + " - " + fsType + " " + escapeMountPath(source) +
         " rw,fmask=0022\n";
}

TEST(Mountinfo, ParsesMountPointSourceAndTypeAndDecodesEscapes) {
  const std::string text =
      "22 1 8:1 / / rw,relatime shared:1 - ext4 /dev/sda1 rw\n"
      "97 22 8:17 / /media/me/LKG\\040P00671 rw,nosuid master:3 propagation_from:1 - vfat /dev/sdb1 rw\n"
      "98 22 0:50 / /mnt/tab\\011new\\012back\\134slash rw - tmpfs none rw\n"
      "garbage line\n"
      "99 22 0:51 / /no/separator rw tmpfs none\n";
  const std::vector<MountEntry> mounts = parseMountinfo(text);
  ASSERT_EQ(mounts.size(), 3u);
  EXPECT_EQ(mounts[0].mountPoint, "/");
  EXPECT_EQ(mounts[1].mountPoint, "/media/me/LKG P00671");
  EXPECT_EQ(mounts[1].source, "/dev/sdb1");
  EXPECT_EQ(mounts[1].fsType, "vfat");
  EXPECT_EQ(mounts[2].mountPoint, "/mnt/tab\tnew\nback\\slash");
}

TEST(Mountinfo, LeavesIncompleteEscapesAlone) {
  EXPECT_EQ(decodeMountinfoField("a\\04"), "a\\04");
  EXPECT_EQ(decodeMountinfoField("a\\999b"), "a\\999b");
  EXPECT_EQ(decodeMountinfoField("\\"), "\\");
  EXPECT_EQ(decodeMountinfoField("x\\101"), "xA");
}

TEST(Mountinfo, ReadsThisProcessesRealTable) {
  std::ifstream in("/proc/self/mountinfo");
  std::stringstream s;
  s << in.rdbuf();
  const std::vector<MountEntry> mounts = parseMountinfo(s.str());
  ASSERT_FALSE(mounts.empty());
  bool hasRoot = false;
  for (const MountEntry& m : mounts) hasRoot |= m.mountPoint == "/";
  EXPECT_TRUE(hasRoot);
}

class DriveScanTest : public ::testing::Test {
 protected:
  ht::test::TempDirectory temp;
  fs::path root() const { return temp.path(); }
  DriveScanOptions options() const { return {root() / "mountinfo", root() / "by-label", 1 << 20}; }
};

TEST_F(DriveScanTest, FindsVisualJsonOnMountedVolumesIncludingEscapedPaths) {
  const fs::path volume = root() / "media" / "me" / "LKG P00671";  // a space: \040 in mountinfo
  writeFile(volume / "LKG_calibration" / "visual.json", fixtureText("portrait_issue3_visual.json"));
  const fs::path other = root() / "media" / "usbstick";
  fs::create_directories(other);
  writeFile(root() / "mountinfo", mountLine(21, "/", "/dev/sda1") + mountLine(40, volume, "/dev/sdb1") +
                                      mountLine(41, other, "/dev/sdc1") + mountLine(42, volume, "/dev/sdb1"));
  const DriveScan scan = scanDrives(options());
  ASSERT_EQ(scan.found.size(), 1u) << "the bind-mounted duplicate is listed once";
  EXPECT_EQ(scan.found[0].file, volume / "LKG_calibration" / "visual.json");
  ASSERT_TRUE(scan.found[0].calibration);
  EXPECT_EQ(scan.found[0].calibration->calibration.serial.substr(0, 5), "LKG-P");
}

TEST_F(DriveScanTest, NetworkAndPseudoFileSystemsAreNotLookedInto) {
  const fs::path share = root() / "share", tmp = root() / "tmp";
  writeFile(share / "LKG_calibration" / "visual.json", fixtureText("go_template_visual.json"));
  writeFile(tmp / "LKG_calibration" / "visual.json", fixtureText("go_template_visual.json"));
  writeFile(root() / "mountinfo", mountLine(1, share, "server:/export", "nfs4") + mountLine(2, tmp, "tmpfs", "tmpfs"));
  EXPECT_TRUE(scanDrives(options()).found.empty());
  writeFile(root() / "mountinfo", mountLine(1, share, "/dev/sdb1", "exfat"));
  EXPECT_EQ(scanDrives(options()).found.size(), 1u);
}

TEST_F(DriveScanTest, ABadVisualJsonIsAnErrorForThatDriveOnly) {
  const fs::path good = root() / "good", bad = root() / "bad", huge = root() / "huge";
  writeFile(good / "LKG_calibration" / "visual.json", fixtureText("go_template_visual.json"));
  writeFile(bad / "LKG_calibration" / "visual.json", "{\"pitch\": ");
  writeFile(huge / "LKG_calibration" / "visual.json", std::string(2000, ' '));
  writeFile(root() / "mountinfo",
            mountLine(1, bad, "/dev/sdb1") + mountLine(2, good, "/dev/sdc1") + mountLine(3, huge, "/dev/sdd1"));
  DriveScanOptions o = options();
  o.maxFileBytes = 1000;
  const DriveScan scan = scanDrives(o);
  ASSERT_EQ(scan.found.size(), 3u);
  ASSERT_TRUE(scan.found[0].error);
  EXPECT_EQ(scan.found[0].error->fault(), DeviceFault::InvalidJson);
  EXPECT_EQ(scan.found[0].error->device(), (bad / "LKG_calibration" / "visual.json").string());
  EXPECT_FALSE(scan.found[0].calibration);
  EXPECT_TRUE(scan.found[1].calibration);
  ASSERT_TRUE(scan.found[2].error);
  EXPECT_EQ(scan.found[2].error->fault(), DeviceFault::FileTooLarge);
}

TEST_F(DriveScanTest, ReportsLabelledVolumesThatAreNotMounted) {
  fs::create_directories(root() / "by-label");
  fs::create_directories(root() / "dev");
  for (const char* node : {"sdb1", "sdc1", "sdd1"}) writeFile(root() / "dev" / node, "");
  fs::create_symlink("../dev/sdb1", root() / "by-label" / "LKG-P00671");  // mounted
  fs::create_symlink("../dev/sdc1", root() / "by-label" / "LKG-J01234");  // not mounted
  fs::create_symlink("../dev/sdd1", root() / "by-label" / "USBSTICK");    // not ours
  writeFile(root() / "mountinfo", mountLine(1, root() / "mnt", (root() / "dev" / "sdb1").string()));
  const DriveScan scan = scanDrives(options());
  ASSERT_EQ(scan.unmounted.size(), 1u);
  EXPECT_EQ(scan.unmounted[0].label, "LKG-J01234");
  EXPECT_EQ(scan.unmounted[0].device, fs::weakly_canonical(root() / "dev" / "sdc1"));
}

TEST_F(DriveScanTest, MissingRootsFindNothing) {
  const DriveScan scan = scanDrives(options());
  EXPECT_TRUE(scan.found.empty());
  EXPECT_TRUE(scan.unmounted.empty());
}

TEST(DeviceTypes, SerialPrefixNamesTheType) {
  ASSERT_NE(deviceTypeOfSerial("LKG-2K01234"), nullptr);
  EXPECT_EQ(deviceTypeOfSerial("LKG-2K01234")->name, "Gen1 8.9\"");
  EXPECT_EQ(deviceTypeOfSerial("LKG-P00671")->screenH, 2048u);
  EXPECT_EQ(deviceTypeOfSerial("LKG-J1")->name, "Gen3 16\" landscape");
  EXPECT_EQ(deviceTypeOfSerial("XYZ"), nullptr);
  EXPECT_EQ(deviceTypeOfSerial(""), nullptr);
}

class DiscoveryTest : public DriveScanTest {
 protected:
  // A fake USB scan returning one Gen1 panel with the given calibration.
  static std::function<UsbScan(const UsbScanOptions&)> usbWith(const std::string& json) {
    return [json](const UsbScanOptions&) {
      UsbScan scan;
      scan.devices.push_back({"USB 001/002 04d8:ef7e HoloPlay", checkCalibrationText(json, "usb"), std::nullopt});
      return scan;
    };
  }
};

TEST_F(DiscoveryTest, ConfigFileThenMountedDriveThenUsbAndEachSerialOnce) {
  const std::string portrait = fixtureText("portrait_issue3_visual.json");
  const std::string gen1 = fixtureText("gen1_8.9_original_visual.json");
  writeFile(root() / "explicit.json", gen1);
  writeFile(root() / "vol" / "LKG_calibration" / "visual.json", portrait);
  writeFile(root() / "mountinfo", mountLine(1, root() / "vol", "/dev/sdb1"));
  DiscoveryOptions o;
  o.calibrationFile = root() / "explicit.json";
  o.drives = options();
  o.usbScanner = usbWith(gen1);  // same serial as the explicit file: left out
  const Discovery d = discoverDevices(o);
  ASSERT_EQ(d.devices.size(), 2u);
  EXPECT_EQ(d.devices[0].source, CalibrationSource::ConfigFile);
  EXPECT_EQ(d.devices[0].serial, "LKG-2K");
  EXPECT_EQ(d.devices[0].deviceType, "Gen1 8.9\"");
  EXPECT_EQ(d.devices[1].source, CalibrationSource::MountedDrive);
  EXPECT_EQ(d.devices[1].deviceType, "Portrait");
  EXPECT_EQ(d.devices[1].matchedMonitor, "");
  ASSERT_EQ(d.notes.size(), 1u);
  EXPECT_NE(d.notes[0].find("usb-hid"), std::string::npos) << d.notes[0];
}

TEST_F(DiscoveryTest, UsbOnlyAndTheSwitchesTurnSourcesOff) {
  DiscoveryOptions o;
  o.drives = options();
  o.usbScanner = usbWith(fixtureText("gen1_8.9_original_visual.json"));
  Discovery d = discoverDevices(o);
  ASSERT_EQ(d.devices.size(), 1u);
  EXPECT_EQ(d.devices[0].source, CalibrationSource::UsbHid);
  EXPECT_TRUE(d.devices[0].loaded());
  o.scanUsb = false;
  EXPECT_TRUE(discoverDevices(o).devices.empty());
}

TEST_F(DiscoveryTest, TheMonitorHookNamesTheMonitorOfLoadedPanelsOnly) {
  writeFile(root() / "explicit.json", fixtureText("portrait_issue3_visual.json"));
  writeFile(root() / "broken.json", "{");
  DiscoveryOptions o;
  o.calibrationFile = root() / "explicit.json";
  o.drives = options();
  o.usbScanner = [](const UsbScanOptions&) {
    UsbScan scan;
    scan.devices.push_back(
        {"USB 001/002", std::nullopt, DeviceError("USB 001/002", DeviceFault::Stall, "endpoint 0x84")});
    return scan;
  };
  o.matchMonitor = [](const FoundDevice& d) {
    return d.calibration->calibration.screenW == 1536 ? MonitorMatch{"LKG-P (DP-1)", ""}
                                                      : MonitorMatch{"", "no monitor"};
  };
  const Discovery d = discoverDevices(o);
  ASSERT_EQ(d.devices.size(), 2u);
  EXPECT_EQ(d.devices[0].matchedMonitor, "LKG-P (DP-1)");
  EXPECT_EQ(d.devices[0].monitorProblem, "");
  EXPECT_EQ(d.devices[1].matchedMonitor, "");
  EXPECT_EQ(d.devices[1].monitorProblem, "") << "the hook is not asked about panels that did not load";
  EXPECT_FALSE(d.devices[1].loaded());
}

TEST_F(DiscoveryTest, ABrokenExplicitFileIsListedWithItsError) {
  writeFile(root() / "explicit.json", "not json");
  DiscoveryOptions o;
  o.calibrationFile = root() / "explicit.json";
  o.scanDrives = false;
  o.scanUsb = false;
  const Discovery d = discoverDevices(o);
  ASSERT_EQ(d.devices.size(), 1u);
  EXPECT_FALSE(d.devices[0].loaded());
  ASSERT_TRUE(d.devices[0].error);
  EXPECT_EQ(d.devices[0].error->fault(), DeviceFault::InvalidJson);
  EXPECT_NE(d.devices[0].problem().find("explicit.json"), std::string::npos);
}

}  // namespace
}  // namespace ht::devices
