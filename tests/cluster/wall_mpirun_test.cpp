// `mpirun -np N holotrace wall` on one private Xvfb with one RandR monitor per rank (docs/CLUSTER.md §7), over shared
// memory and loopback only: each rank's window shows exactly the single-process render of its projectors (the
// pixels read back from the X server equal `holotrace render --layout views`'s PNGs of the last frame), every rank
// presents every frame, a rank delayed by the test hook is reported late while the job still finishes with every
// rank on the last frame, and a killed rank ends the job on every rank within seconds.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <thread>

#include "frame_io/image_reading.h"
#include "frame_io/pixel_encoding.h"
#include "present/screen_capture.h"
#include "present/xvfb_server.h"
#include "tests/cli/process_runner.h"
#include "tests/cluster/mpirun_launcher.h"
#include "tests/common/temp_directory.h"

namespace ht::test {
namespace {

namespace fs = std::filesystem;
using cli::test::ProcessResult;
using ::testing::HasSubstr;

// Four 32x24 projectors; frame f is rendered with seed --seed + f.
const char* const kWall = R"({"name": "wall-tiny", "model": "projector-array",
  "camera": {"target": "auto", "size": "auto"}, "spp": 2,
  "projectorArray": {"screen": {"width": 800, "height": 600}, "observerDistance": 2500, "observerHeight": 0,
    "angularScattering": 0.02, "image": {"width": 32, "height": 24},
    "projectors": [{"position": [-300, 0, -1500]}, {"position": [-100, 0, -1500]},
                   {"position": [100, 0, -1500]}, {"position": [300, 0, -1500]}]}})";
constexpr std::uint32_t kView = 32, kViewHeight = 24;
constexpr std::uint32_t kLastSeed = 11;  // the last frame's seed in every run below

struct RankWindow {
  std::vector<std::uint32_t> projectors;
  present::Rect rect;
};

class WallMpirun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    shaderCache_ = new fs::path(prepareMpirunEnvironment());
    suiteDir_ = new fs::path(fs::temp_directory_path() / ("holotrace-wall-test-" + std::to_string(getpid())));
    fs::create_directories(*suiteDir_);
    std::ofstream(config()) << kWall;
  }
  // The reference: `holotrace render` of the last frame alone, one PNG per view.
  static void renderReference() {
    const ProcessResult r =
        cli::test::runProcess(HOLOTRACE_EXE, {"render", "--display", config(), "--scene", "builtin:sphere", "--seed",
                                              std::to_string(kLastSeed), "--layout", "views", "-o", png("frame")});
    ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  }
  static void TearDownTestSuite() {
    std::error_code ignored;
    fs::remove_all(*shaderCache_, ignored);
    fs::remove_all(*suiteDir_, ignored);
    delete shaderCache_;
    delete suiteDir_;
    shaderCache_ = suiteDir_ = nullptr;
  }

  static std::string config() { return (*suiteDir_ / "wall.json").string(); }
  static std::string png(const std::string& stem) { return (*suiteDir_ / (stem + ".png")).string(); }

  // One monitor per rank, side by side; the layout names them.
  std::string setUpScreens(present::XvfbServer& xvfb, const std::vector<RankWindow>& windows) const {
    std::string layout = "{\"ranks\": [";
    for (std::size_t r = 0; r < windows.size(); ++r) {
      const std::string name = "WALL-" + std::to_string(r);
      xvfb.setMonitor(name, windows[r].rect, {});
      layout += std::string(r ? ", " : "") + "{\"monitor\": \"" + name + "\", \"projectors\": [";
      for (std::size_t i = 0; i < windows[r].projectors.size(); ++i)
        layout += (i ? ", " : "") + std::to_string(windows[r].projectors[i]);
      layout += "]}";
    }
    const fs::path path = dir_.path() / "layout.json";
    std::ofstream(path) << layout << "]}";
    return path.string();
  }

  // The RGB bytes rank window `w` must show: its projectors' PNGs side by side.
  static std::vector<std::uint8_t> expectedWindow(const RankWindow& w) {
    std::vector<std::uint8_t> rgb(std::size_t(w.rect.width) * w.rect.height * 3);
    for (std::size_t t = 0; t < w.projectors.size(); ++t) {
      char name[16];
      std::snprintf(name, sizeof name, "frame_v%02u", w.projectors[t]);
      const frame_io::ImageFile image = frame_io::readImageFile(png(name));
      EXPECT_EQ(image.width, kView);
      for (std::uint32_t y = 0; y < kViewHeight; ++y)
        for (std::uint32_t x = 0; x < kView; ++x)
          for (int c = 0; c < 3; ++c)
            rgb[((y * w.rect.width) + t * kView + x) * 3 + c] =
                frame_io::srgbEncode8(image.rgba[(std::size_t(y) * kView + x) * 4 + c]);
    }
    return rgb;
  }

  // Runs the wall and watches the screen meanwhile: true per window once it showed exactly the expected pixels.
  ProcessResult runWatching(present::XvfbServer& xvfb, const std::vector<RankWindow>& windows,
                            const std::vector<std::string>& wallArgs, std::vector<bool>& matched) {
    std::vector<std::string> args = kLauncherFlags;
    args.insert(args.end(), {"-np", std::to_string(windows.size()), HOLOTRACE_EXE, "wall", "--display", config(),
                             "--scene", "builtin:sphere", "--x-display", xvfb.display(), "--hold", "2"});
    args.insert(args.end(), wallArgs.begin(), wallArgs.end());
    renderReference();  // before the job: runProcess's capture files are named by this process's PID
    std::atomic<bool> done{false};
    ProcessResult result;
    std::thread job([&] {
      result = launchMpirun(args);
      done = true;
    });
    std::vector<std::vector<std::uint8_t>> expected;
    for (const RankWindow& w : windows) expected.push_back(expectedWindow(w));
    matched.assign(windows.size(), false);
    while (!done) {
      for (std::size_t r = 0; r < windows.size(); ++r)
        if (!matched[r]) matched[r] = present::captureRgb(xvfb.connection(), windows[r].rect) == expected[r];
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    job.join();
    return result;
  }

  TempDirectory dir_;
  static fs::path* shaderCache_;
  static fs::path* suiteDir_;
};
fs::path* WallMpirun::shaderCache_ = nullptr;
fs::path* WallMpirun::suiteDir_ = nullptr;

TEST_F(WallMpirun, EachRankShowsItsProjectorsAsTheSingleProcessRenderAndAllPresentEveryFrame) {
  present::XvfbServer xvfb(128, 48);
  const std::vector<RankWindow> windows = {{{0, 1}, {0, 0, 64, 24}}, {{2, 3}, {64, 0, 64, 24}}};
  const std::string layout = setUpScreens(xvfb, windows);
  std::vector<bool> matched;
  const ProcessResult m = runWatching(
      xvfb, windows, {"--layout", layout, "--frames", "3", "--seed", "9", "--swap-timeout", "2000"}, matched);
  ASSERT_EQ(m.exitCode, 0) << m.err << m.out;
  EXPECT_TRUE(matched[0]) << "rank 0's window never showed projectors 0 and 1 of the last frame\n" << m.out;
  EXPECT_TRUE(matched[1]) << "rank 1's window never showed projectors 2 and 3 of the last frame\n" << m.out;
  EXPECT_THAT(m.out, HasSubstr("rank 0: presented 3 (on time 3, timed out 0), late 0, skipped 0"));
  EXPECT_THAT(m.out, HasSubstr("rank 1: presented 3 (on time 3, timed out 0), late 0, skipped 0"));
  EXPECT_THAT(m.out, HasSubstr("swap: 3 frame(s) shown by every rank on time"));
}

TEST_F(WallMpirun, ADelayedRankIsReportedLateAndTheJobFinishesOnTheSameLastFrame) {
  present::XvfbServer xvfb(128, 48);
  const std::vector<RankWindow> windows = {{{0, 1}, {0, 0, 64, 24}}, {{2}, {64, 0, 32, 24}}, {{3}, {96, 0, 32, 24}}};
  const std::string layout = setUpScreens(xvfb, windows);
  std::vector<bool> matched;
  // Rank 1 sleeps 900 ms after rendering frame 1; the others wait at most 200 ms per frame. (With a 50 ms wait, a
  // loaded machine -- two ctest jobs beside two busy loops on two cores -- made rank 0 late on its own by 16 ms.)
  const ProcessResult m = runWatching(
      xvfb, windows, {"--layout", layout, "--frames", "12", "--swap-timeout", "200", "--debug-rank-delay", "1:1:900"},
      matched);
  ASSERT_EQ(m.exitCode, 0) << m.err << m.out;
  EXPECT_THAT(m.out, HasSubstr("late: rank 1, frame 1, by "));
  EXPECT_THAT(m.err, HasSubstr("rank 1 of 3: frame 1: late for the swap by "));
  EXPECT_THAT(m.err, HasSubstr("presented without the late rank(s)"));
  EXPECT_THAT(m.out, HasSubstr("rank 0: presented 12"));
  EXPECT_THAT(m.out, HasSubstr("rank 2: presented 12"));
  for (std::size_t r = 0; r < windows.size(); ++r) EXPECT_TRUE(matched[r]) << "rank " << r << "\n" << m.out << m.err;
}

TEST_F(WallMpirun, AKilledRankEndsEveryRankWithinSeconds) {
  present::XvfbServer xvfb(128, 48);
  const std::vector<RankWindow> windows = {{{0, 1}, {0, 0, 64, 24}}, {{2, 3}, {64, 0, 64, 24}}};
  const std::string layout = setUpScreens(xvfb, windows);
  std::vector<std::string> args = kLauncherFlags;
  args.insert(args.end(),
              {"-x", "HOLOTRACE_TEST_KILL_RANK=1", "-np", "2", HOLOTRACE_EXE, "wall", "--display", config(), "--scene",
               "builtin:sphere", "--x-display", xvfb.display(), "--layout", layout, "--frames", "100000"});
  const auto start = std::chrono::steady_clock::now();
  const ProcessResult m = launchMpirun(args);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(m.exitCode, 0) << m.out;
  EXPECT_LT(seconds, 60.0) << m.err;  // the whole job, start-up included (slow under the ASan suite's load)
  // After the kill rank 0 flips alone, one timed-out frame per 100 ms swap timeout: the count of those lines bounds
  // how long it outlived rank 1.
  std::size_t alone = 0;
  for (std::size_t at = m.err.find("presented without the late rank"); at != std::string::npos;
       at = m.err.find("presented without the late rank", at + 1))
    ++alone;
  EXPECT_LT(alone, 50u) << "rank 0 kept flipping alone for more than 5 s after rank 1 died\n" << m.err;
}

}  // namespace
}  // namespace ht::test
