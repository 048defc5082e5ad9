// umockdev_test.cpp - the Gen1 USB path end to end: `holotrace devices` reads an emulated panel through libusb and
// the kernel's usbdevfs interface as umockdev replays it (umockdev_panel.h writes the device and its URBs from a
// fixture JSON). Skips with a message when umockdev-run is not installed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/cli/process_runner.h"
#include "tests/common/temp_directory.h"
#include "tests/devices/umockdev_panel.h"

namespace ht::devices::test {
namespace {

namespace fs = std::filesystem;

std::string findUmockdevRun() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir) / "umockdev-run";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

std::string gen1Fixture() {
  std::ifstream in(std::string(HT_TEST_DATA_DIR) + "/configs/gen1_8.9_original_visual.json", std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class UmockdevPanel : public ::testing::Test {
 protected:
  void SetUp() override {
    umockdevRun_ = findUmockdevRun();
    if (umockdevRun_.empty()) {
      GTEST_SKIP() << "umockdev-run is not installed (Debian: apt-get install umockdev; scripts/install-deps.sh): "
                      "the libusb end-to-end tests of the Gen1 USB path are skipped";
    }
    // The preload library comes before the ASan runtime under umockdev-run (ASan builds only; harmless otherwise).
    const char* asan = std::getenv("ASAN_OPTIONS");
    ::setenv("ASAN_OPTIONS", (std::string(asan ? asan : "") + ":verify_asan_link_order=0").c_str(), 1);
  }

  // Runs `holotrace devices --json` (USB only) against the emulated panel; returns the result and the one JSON line.
  cli::test::ProcessResult listDevices(const EmulatedPanel& panel, nlohmann::json& line) {
    const fs::path device = temp_.path() / "lkg.umockdev", ioctl = temp_.path() / "lkg.ioctl";
    std::ofstream(device) << umockdevDeviceText();
    std::ofstream(ioctl) << umockdevIoctlText(panel);
    cli::test::ProcessResult result = cli::test::runProcess(
        umockdevRun_, {"-d", device.string(), "-i", std::string(kEmulatedNode) + "=" + ioctl.string(), "--",
                       HOLOTRACE_EXE, "devices", "--json", "--no-drives", "--usb-timeout-ms", "500"});
    std::istringstream lines(result.out);
    std::string first, extra;
    std::getline(lines, first);
    EXPECT_FALSE(std::getline(lines, extra)) << "one panel expected:\n" << result.out;
    line = nlohmann::json::parse(first, nullptr, false);
    EXPECT_TRUE(line.is_object()) << "stdout: " << result.out << "\nstderr: " << result.err;
    return result;
  }

  // A panel whose read must fail with `fault`; nothing of it may be loaded.
  void expectFault(const EmulatedPanel& panel, const std::string& fault, const std::string& detail) {
    nlohmann::json line;
    const cli::test::ProcessResult result = listDevices(panel, line);
    EXPECT_EQ(result.exitCode, 1) << result.err;
    if (!line.is_object()) return;
    EXPECT_EQ(line.value("fault", ""), fault) << line.dump();
    EXPECT_EQ(line.value("loaded", true), false);
    EXPECT_EQ(line.value("serial", "?"), "");
    EXPECT_EQ(line.value("source", ""), "usb-hid");
    const std::string problem = line.value("problem", "");
    EXPECT_NE(problem.find("USB 001/002 04d8:ef7e HoloPlay"), std::string::npos) << problem;
    EXPECT_NE(problem.find(detail), std::string::npos) << problem;
    EXPECT_NE(result.err.find("could not be loaded"), std::string::npos) << result.err;
  }

  void expectLoaded(const EmulatedPanel& panel) {
    nlohmann::json line;
    const cli::test::ProcessResult result = listDevices(panel, line);
    EXPECT_EQ(result.exitCode, 0) << result.err;
    if (!line.is_object()) return;
    EXPECT_EQ(line.value("loaded", false), true) << line.dump();
    EXPECT_EQ(line.value("serial", ""), "LKG-2K");
    EXPECT_EQ(line.value("type", ""), "Gen1 8.9\"");
    EXPECT_EQ(line.value("source", ""), "usb-hid");
    EXPECT_EQ(line.value("location", ""), "USB 001/002 04d8:ef7e HoloPlay");
    EXPECT_EQ(line.value("screenW", 0), 2560);
    EXPECT_EQ(line.value("screenH", 0), 1600);
  }

  ht::test::TempDirectory temp_;
  std::string umockdevRun_;
};

TEST_F(UmockdevPanel, GoodPanelLoadsThroughLibusb) { expectLoaded({gen1Fixture()}); }

TEST_F(UmockdevPanel, RepliesSplitInto64Plus4BytesAreReassembled) {
  EmulatedPanel panel{gen1Fixture()};
  panel.splitReplies = true;
  expectLoaded(panel);
}

TEST_F(UmockdevPanel, CorruptedPageEchoIsAnEchoMismatch) {
  EmulatedPanel panel{gen1Fixture()};
  panel.echo[1] = 6;  // page 1's reply claims page 6; the panel's later replies do not echo page 1 either
  expectFault(panel, "echo-mismatch", "asked for page 1");
}

TEST_F(UmockdevPanel, AShortPageIsATruncatedReport) {
  EmulatedPanel panel{gen1Fixture()};
  panel.cut[2] = 40;
  expectFault(panel, "truncated-report", "page 2: the reply stopped after 40 of 68 bytes");
}

TEST_F(UmockdevPanel, AStalledEndpointIsAStall) {
  EmulatedPanel panel{gen1Fixture()};
  panel.stallPage = 3;
  expectFault(panel, "stall", "LIBUSB_ERROR_PIPE");
}

}  // namespace
}  // namespace ht::devices::test
