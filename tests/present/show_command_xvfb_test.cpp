// show_command_xvfb_test.cpp - `holotrace show` end to end on a private Xvfb: the binary renders the tiny panel
// config, finds the LKG monitor, keeps the frame up (the bytes on screen equal `holotrace render -o`'s PNG) until
// SIGTERM, then exits 0.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <set>

#include "present/edid.h"
#include "present/xvfb_server.h"
#include "tests/present/screen_check.h"

namespace ht::present {
namespace {

const Rect kShowPanel{160, 0, 96, 128};
const std::string kConfig = std::string(HT_TEST_DATA_DIR) + "/configs/xvfb_panel_96x128.json";

pid_t startHolotrace(const std::vector<std::string>& args, const std::filesystem::path& log) {
  return test::startProcess(HOLOTRACE_EXE, args, log);
}

TEST(ShowCommandXvfb, KeepsTheRenderedFrameOnThePanelUntilSigterm) {
  XvfbServer xvfb(256, 128);
  xvfb.setEdid("screen", makeEdid("LKG-P0001"));
  xvfb.setMonitor("MAIN", {0, 0, 160, 128}, {});
  xvfb.setMonitor("LKG-P", kShowPanel, {"screen"});
  const auto dir = std::filesystem::temp_directory_path() / ("ht_show_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto png = dir / "panel.png";

  pid_t show = startHolotrace({"show", "--display", kConfig, "--scene", "builtin:plain", "--x-display", xvfb.display()},
                              dir / "show.log");
  pid_t render = startHolotrace({"render", "--display", kConfig, "--scene", "builtin:plain", "-o", png.string()},
                                dir / "render.log");
  ASSERT_EQ(test::waitExit(render), 0) << test::readText(dir / "render.log");
  const std::vector<std::uint8_t> expected = test::pngRgb(png);
  ASSERT_EQ(expected.size(), std::size_t(96) * 128 * 3);
  ASSERT_GE(std::set<std::uint8_t>(expected.begin(), expected.end()).size(), 8u) << "a frame with content";

  const std::size_t bad = test::screenMismatches(xvfb.connection(), kShowPanel, expected, std::chrono::seconds(60));
  EXPECT_EQ(bad, 0u) << test::readText(dir / "show.log");
  kill(show, SIGTERM);
  EXPECT_EQ(test::waitExit(show), 0) << test::readText(dir / "show.log");
  const std::string log = test::readText(dir / "show.log");
  EXPECT_NE(log.find("showing on monitor LKG-P 96x128+160+0 (EDID LKG"), std::string::npos) << log;
  EXPECT_NE(log.find("stopped: presented"), std::string::npos) << log;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ht::present
