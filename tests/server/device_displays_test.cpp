// device_displays_test.cpp - Looking Glass panels found on the host become daemon displays "device:SERIAL": the
// "devices" config section, the registry with an injected scan (loaded / failed panels, rescans), and an in-process
// daemon whose ListDisplays shows a panel found on an (injected) mounted drive, with its source, before and after a
// reload (SIGHUP).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "common/error.h"
#include "devices/loaded_calibration.h"
#include "server/display_messages.h"
#include "server/display_registry.h"
#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

std::string visualJson(const std::string& fixture) {
  std::ifstream in(std::string(HT_TEST_DATA_DIR) + "/configs/" + fixture, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(DeviceDisplayConfig, ParsesTheDevicesSection) {
  const DaemonConfig c = parseDaemonConfig(
      R"({"scene_root": "s", "output_root": "o", "devices": {"usb": false, "calibration_file": "lkg.json",
          "detach_kernel_driver": false, "mountinfo": "/m", "by_label_dir": "l"}})",
      "t.json", "/base");
  EXPECT_TRUE(c.devices.scan);
  EXPECT_TRUE(c.devices.drives);
  EXPECT_FALSE(c.devices.usb);
  EXPECT_FALSE(c.devices.detachKernelDriver);
  EXPECT_EQ(c.devices.calibrationFile, std::filesystem::path("/base/lkg.json"));
  EXPECT_EQ(c.devices.mountinfo, std::filesystem::path("/m"));
  EXPECT_EQ(c.devices.byLabelDir, std::filesystem::path("/base/l"));
  EXPECT_TRUE(parseDaemonConfig(R"({"scene_root": "s", "output_root": "o"})", "t.json", "/").devices.scan);
  EXPECT_FALSE(deviceScanFor(
      parseDaemonConfig(R"({"scene_root": "s", "output_root": "o", "devices": {"scan": false}})", "t.json", "/")
          .devices));
}

TEST(DeviceDisplayConfig, RejectsUnknownKeysAndWrongTypesNamingTheField) {
  for (const auto& [text, field] :
       std::vector<std::pair<std::string, std::string>>{{R"({"devices": {"usbb": true}})", "devices.usbb"},
                                                        {R"({"devices": {"usb": "yes"}})", "devices.usb"},
                                                        {R"({"devices": []})", "devices"}}) {
    try {
      parseDaemonConfig(R"({"scene_root": "s", "output_root": "o", )" + text.substr(1), "t.json", "/");
      ADD_FAILURE() << "accepted " << text;
    } catch (const ConfigError& e) { EXPECT_EQ(e.field(), field); }
  }
}

// A scan that reports one loaded Gen1 panel and one that failed; the second call adds a Portrait.
DeviceScan scriptedScan(int& calls) {
  return [&calls] {
    devices::Discovery d;
    devices::FoundDevice gen1;
    gen1.source = devices::CalibrationSource::UsbHid;
    gen1.location = "USB 001/002 04d8:ef7e HoloPlay";
    gen1.calibration = devices::checkCalibrationText(visualJson("gen1_8.9_original_visual.json"), gen1.location);
    gen1.serial = "LKG-2K";
    d.devices.push_back(gen1);
    devices::FoundDevice broken;
    broken.source = devices::CalibrationSource::UsbHid;
    broken.location = "USB 001/003 04d8:ef7e HoloPlay";
    broken.error = devices::DeviceError(broken.location, devices::DeviceFault::EchoMismatch, "asked for page 1");
    d.devices.push_back(broken);
    if (++calls > 1) {
      devices::FoundDevice portrait;
      portrait.source = devices::CalibrationSource::MountedDrive;
      portrait.location = "/media/lkg/LKG_calibration/visual.json";
      portrait.calibration = devices::checkCalibrationText(visualJson("portrait_pr56_visual.json"), portrait.location);
      portrait.serial = portrait.calibration->calibration.serial;
      d.devices.push_back(portrait);
    }
    return d;
  };
}

TEST(DeviceDisplayRegistry, LoadedPanelsBecomeDisplaysWithTheirSourceAndFailedOnesAreLogged) {
  int calls = 0;
  DisplayRegistry registry("", scriptedScan(calls));
  std::ostringstream log;
  const std::size_t first = registry.reload(log);
  const auto gen1 = registry.find("device:LKG-2K");
  EXPECT_EQ(gen1->source, "usb-hid");
  EXPECT_EQ(gen1->serial, "LKG-2K");
  ASSERT_TRUE(gen1->config.calibration);
  EXPECT_EQ(gen1->config.calibration->screenW, 2560u);
  EXPECT_EQ(gen1->sourceText, visualJson("gen1_8.9_original_visual.json"));
  EXPECT_NE(log.str().find("panel skipped: USB 001/003 04d8:ef7e HoloPlay: echo-mismatch"), std::string::npos)
      << log.str();
  EXPECT_EQ(registry.find("builtin:portrait")->source, "builtin");

  holotrace::v1::DisplaySummary summary;
  fillDisplaySummary(*gen1, summary);
  EXPECT_EQ(summary.source(), "usb-hid");
  EXPECT_EQ(summary.serial(), "LKG-2K");
  EXPECT_EQ(summary.panel_width(), 2560u);

  // A rescan (SIGHUP) picks up the panel that appeared since.
  EXPECT_EQ(registry.reload(log), first + 1);
  bool portrait = false;
  for (const auto& d : registry.list()) portrait |= d->source == "mounted-drive" && d->id.rfind("device:", 0) == 0;
  EXPECT_TRUE(portrait);
}

// The daemon itself: panels from an injected mount table, ListDisplays with sources, reloadDisplays() = SIGHUP.
TEST(DeviceDisplayDaemon, ListDisplaysShowsPanelsFoundOnMountedDrivesAndReloadRescans) {
  DaemonFiles files;
  const std::filesystem::path vol1 = files.dir.path / "media" / "LKG P1", vol2 = files.dir.path / "media" / "LKG-J";
  writeText(vol1 / "LKG_calibration" / "visual.json", visualJson("portrait_pr56_visual.json"));
  writeText(vol2 / "LKG_calibration" / "visual.json", visualJson("gen3_16_landscape_visual.json"));
  const auto mountLine = [](int id, const std::filesystem::path& dir) {
    std::string escaped;
    for (char ch : dir.string()) escaped += ch == ' ' ? std::string("\\040") : std::string(1, ch);
    return std::to_string(id) + " 1 8:1 / " + escaped + " rw - vfat /dev/sdx" + std::to_string(id) + " rw\n";
  };
  const std::filesystem::path mountinfo = files.dir.path / "mountinfo";
  writeText(mountinfo, mountLine(1, vol1));
  DaemonConfig config = files.config();
  config.devices.usb = false;
  config.devices.mountinfo = mountinfo;
  config.devices.byLabelDir = files.dir.path / "no-labels";
  std::ostringstream log;
  Daemon daemon(config, log);
  daemon.start();
  const auto stub = connect(files.socketAddress());

  const auto deviceDisplays = [&] {
    grpc::ClientContext context;
    v1::ListDisplaysResponse response;
    EXPECT_TRUE(stub->ListDisplays(&context, {}, &response).ok());
    std::vector<v1::DisplaySummary> found;
    for (const auto& d : response.displays()) {
      if (d.id().rfind("device:", 0) == 0)
        found.push_back(d);
      else
        EXPECT_TRUE(d.source() == "builtin" || d.source() == "displays-dir") << d.id() << " " << d.source();
    }
    return found;
  };
  std::vector<v1::DisplaySummary> found = deviceDisplays();
  ASSERT_EQ(found.size(), 1u) << log.str();
  EXPECT_EQ(found[0].source(), "mounted-drive");
  EXPECT_EQ(found[0].panel_width(), 1536u);
  EXPECT_EQ(found[0].id(), "device:" + found[0].serial());

  writeText(mountinfo, mountLine(1, vol1) + mountLine(2, vol2));
  daemon.reloadDisplays();
  found = deviceDisplays();
  ASSERT_EQ(found.size(), 2u) << log.str();
  daemon.shutdown(std::chrono::milliseconds(0));
}

}  // namespace
}  // namespace ht::server::test
