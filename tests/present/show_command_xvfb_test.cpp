// show_command_xvfb_test.cpp - `holotrace show` end to end on a private Xvfb: the binary renders the tiny panel
// config, finds the LKG monitor, keeps the frame up (the bytes on screen equal `holotrace render -o`'s PNG) until
// SIGTERM, then exits 0.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "frame_io/image_reading.h"
#include "frame_io/pixel_encoding.h"
#include "present/edid.h"
#include "present/screen_capture.h"
#include "present/xvfb_server.h"

namespace ht::present {
namespace {

const Rect kShowPanel{160, 0, 96, 128};
const std::string kConfig = std::string(HT_TEST_DATA_DIR) + "/configs/xvfb_panel_96x128.json";

// Starts `holotrace args...` with stdout and stderr into `log`; returns its PID.
pid_t startHolotrace(const std::vector<std::string>& args, const std::filesystem::path& log) {
  std::vector<std::string> argv = {HOLOTRACE_EXE};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargs;
  for (std::string& a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  const std::string logPath = log.string();
  pid_t pid = fork();
  if (pid == 0) {
    FILE* f = std::fopen(logPath.c_str(), "w");
    if (f) {
      dup2(fileno(f), STDOUT_FILENO);
      dup2(fileno(f), STDERR_FILENO);
    }
    execv(cargs[0], cargs.data());
    _exit(127);
  }
  return pid;
}

int waitExit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::uint8_t> pngRgbOf(const std::filesystem::path& png) {
  frame_io::ImageFile image = frame_io::readImageFile(png);
  std::vector<std::uint8_t> rgb;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) rgb.push_back(frame_io::srgbEncode8(image.rgba[i + c]));
  }
  return rgb;
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
  ASSERT_EQ(waitExit(render), 0) << readText(dir / "render.log");
  const std::vector<std::uint8_t> expected = pngRgbOf(png);
  ASSERT_EQ(expected.size(), std::size_t(96) * 128 * 3);
  ASSERT_GE(std::set<std::uint8_t>(expected.begin(), expected.end()).size(), 8u) << "a frame with content";

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::size_t bad = expected.size();
  while (bad != 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    auto screen = captureRgb(xvfb.connection(), kShowPanel);
    bad = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) bad += screen[i] != expected[i];
  }
  EXPECT_EQ(bad, 0u) << readText(dir / "show.log");
  kill(show, SIGTERM);
  EXPECT_EQ(waitExit(show), 0) << readText(dir / "show.log");
  const std::string log = readText(dir / "show.log");
  EXPECT_NE(log.find("showing on monitor LKG-P 96x128+160+0 (EDID LKG"), std::string::npos) << log;
  EXPECT_NE(log.find("stopped: presented"), std::string::npos) << log;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ht::present
