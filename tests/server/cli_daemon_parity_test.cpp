// cli_daemon_parity_test.cpp - for the same request, `holotrace render` (run in-process) and the daemon's Capture
// (in-process daemon on a unix socket) write byte-identical files with the same names: every display model of the
// test daemon (lenticular panel, pinhole, integral, ray-table, capture-grid, oblique, projector-array), every layout
// (auto, quilt, views) and both formats (PNG, EXR). Both package through frame_io::packageFrame; the test also proves
// they render the same frame (same scene, camera placement, seed and spp). A layout a display cannot take is refused
// by both before rendering, and RenderFrame's PNG is the captured file. The lenticular quilt path is
// cli_daemon_quilt_parity_test.cpp (its device default quilt is 3360x3360).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>

#include "tests/server/cli_daemon_parity.h"

namespace ht::server::test {
namespace {

class CliDaemonParityTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    files_ = new DaemonFiles();
    writeMoreDisplays(files_->dir.path / "displays");
    daemon_ = new Daemon(files_->config(), std::cerr);
    daemon_->start();
  }
  static void TearDownTestSuite() {
    delete daemon_;
    delete files_;
  }
  void SetUp() override {
    stub_ = connect(files_->socketAddress());
    v1::SceneHandle handle;
    ASSERT_TRUE(loadScene(*stub_, "builtin:plain", &handle).ok());
    sceneId_ = handle.scene_id();
  }
  ParityCase parityCase(const std::string& display) const { return {display, sceneId_, "builtin:plain"}; }

  static inline DaemonFiles* files_ = nullptr;
  static inline Daemon* daemon_ = nullptr;
  std::unique_ptr<v1::Holotrace::Stub> stub_;
  std::string sceneId_;
};

// One view (the layout changes nothing): lenticular panel, pinhole, integral LCD, ray table.
TEST_F(CliDaemonParityTest, SingleViewModels) {
  ParityRunner runner(*files_, *stub_);
  for (const char* display : {"tiny", "pin", "lens", "table"}) {
    ParityCase c = parityCase(display);
    c.singleView = true;
    runner.check(c);
  }
  EXPECT_EQ(runner.compared(), 4u * 3u * 2u);  // models x layouts x formats, one file each
}

// Views forming a quilt: quilt PNG + JSON (auto, quilt), one PNG per view (views), a multiView EXR.
TEST_F(CliDaemonParityTest, CaptureGridAndObliqueViews) {
  ParityRunner runner(*files_, *stub_);
  runner.check(parityCase("rig"));
  runner.check(parityCase("obl"));
  // Per model: auto and quilt 2 files + 1 EXR each, views 6 or 9 PNGs + 1 EXR.
  EXPECT_EQ(runner.compared(), (3u + 3u + 7u) + (3u + 3u + 10u));
}

// Views forming no quilt: one PNG per view (auto, views); layout quilt refused by both before rendering.
TEST_F(CliDaemonParityTest, ProjectorArrayViews) {
  ParityRunner runner(*files_, *stub_);
  runner.check(parityCase("wall"));
  EXPECT_EQ(runner.compared(), 2u * (3u + 1u));
  EXPECT_THAT(filesWithStem(files_->outputRoot(), "wall_quilt"), ::testing::IsEmpty());
  EXPECT_THAT(filesWithStem(runner.cliDir(), "wall_quilt"), ::testing::IsEmpty());
}

// RenderFrame's PNG is the file Capture and the CLI write: the panel image, and a quilt with its metadata embedded.
TEST_F(CliDaemonParityTest, StreamedPngIsTheCapturedFile) {
  ParityRunner runner(*files_, *stub_);
  for (const auto& [display, file] :
       std::map<std::string, std::string>{{"tiny", "tiny_auto_f0000.png"}, {"rig", "rig_auto_f0000_qs3x2a1.5.png"}}) {
    ParityCase c = parityCase(display);
    c.layouts = {"auto"};
    c.formats = {v1::CAPTURE_FORMAT_PNG};
    runner.check(c);
    v1::RenderRequest render = tinyRequest(sceneId_, v1::PIXEL_FORMAT_PNG);
    render.set_display_id(display);
    render.set_seed(kParitySeed);
    render.set_spp(c.spp);
    ReceivedFrame frame;
    ASSERT_TRUE(renderOne(*stub_, render, &frame).ok()) << display;
    EXPECT_TRUE(frame.bytes == fileBytes(runner.cliDir() / file)) << display;
  }
}

}  // namespace
}  // namespace ht::server::test
