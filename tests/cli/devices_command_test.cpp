// devices_command_test.cpp - `holotrace devices` in-process on injected sources (no USB, no system drives): the
// table and --json output, the exit status when a panel fails to load, usage errors. umockdev runs the USB path
// end to end (tests/devices/umockdev_test.cpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_app.h"

namespace ht::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

struct DevicesRun {
  int code;
  std::string out, err;
};

// Only the explicit file is looked at: USB off, drive roots that do not exist, no X server asked for monitors (the
// MONITOR column is tested on Xvfb, tests/present/devices_monitor_xvfb_test.cpp).
DevicesRun runDevicesOnly(std::vector<std::string> extra) {
  std::vector<std::string> args = {"devices",
                                   "--no-usb",
                                   "--no-monitors",
                                   "--mountinfo",
                                   "/nonexistent/mountinfo",
                                   "--by-label",
                                   "/nonexistent/by-label"};
  args.insert(args.end(), extra.begin(), extra.end());
  std::ostringstream out, err;
  const int code = runCli(args, out, err);
  return {code, out.str(), err.str()};
}

const std::string kGen1 = std::string(HT_TEST_DATA_DIR) + "/configs/gen1_8.9_original_visual.json";

TEST(DevicesCommand, IsListedInTheHelpAndHasItsOwn) {
  EXPECT_THAT(runDevicesOnly({"--help"}).out, StartsWith("Usage: holotrace devices"));
  std::ostringstream out, err;
  runCli(std::vector<std::string>{"--help"}, out, err);
  EXPECT_THAT(out.str(), HasSubstr("  devices "));
}

TEST(DevicesCommand, NothingFoundIsNoError) {
  const DevicesRun r = runDevicesOnly({});
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_EQ(r.out, "no Looking Glass panels found\n");
}

TEST(DevicesCommand, AnExplicitCalibrationIsListedWithTypeAndSource) {
  DevicesRun r = runDevicesOnly({"--calibration", kGen1});
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_THAT(r.out, HasSubstr("LKG-2K        Gen1 8.9\"             config-file       -         " + kGen1));
  r = runDevicesOnly({"--calibration", kGen1, "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const nlohmann::json line = nlohmann::json::parse(r.out);
  EXPECT_EQ(line["serial"], "LKG-2K");
  EXPECT_EQ(line["type"], "Gen1 8.9\"");
  EXPECT_EQ(line["source"], "config-file");
  EXPECT_EQ(line["monitor"], "");
  EXPECT_EQ(line["loaded"], true);
  EXPECT_EQ(line["screenW"], 2560);
}

TEST(DevicesCommand, APanelThatFailsToLoadIsListedWithItsProblemAndExitsOne) {
  const DevicesRun r = runDevicesOnly({"--calibration", std::string(HT_TEST_DATA_DIR) + "/configs/README.md"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_THAT(r.out, HasSubstr("problem: " + std::string(HT_TEST_DATA_DIR) + "/configs/README.md: invalid-json"));
  EXPECT_THAT(r.err, HasSubstr("1 panel(s) could not be loaded"));
}

TEST(DevicesCommand, BadOptionValuesAreUsageErrors) {
  EXPECT_EQ(runDevicesOnly({"--usb-timeout-ms", "0"}).code, kExitUsage);
  EXPECT_EQ(runDevicesOnly({"--usb-timeout", "5"}).code, kExitUsage);
}

}  // namespace
}  // namespace ht::cli
