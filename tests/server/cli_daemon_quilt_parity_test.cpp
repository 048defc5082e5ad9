// cli_daemon_quilt_parity_test.cpp - cli_daemon_parity_test.cpp for the one case too large for the small test
// displays: a lenticular display through its quilt cameras (`--quilt`, RenderRequest.quilt) at the device default
// quilt, 48 views of 420x560 tiled 8x6 into 3360x3360 for the Portrait. The quilt PNG with the calibration in its
// metadata and the multiView EXR are byte-identical from the CLI and Capture. A 12-triangle scene keeps it lean.
#include <gtest/gtest.h>

#include "tests/server/cli_daemon_parity.h"

namespace ht::server::test {
namespace {

TEST(CliDaemonQuiltParityTest, PortraitQuiltPngAndMultiViewExr) {
  DaemonFiles files;
  DaemonConfig config = files.config();
  config.limits.maxPanelPixels = 3360u * 3360u;  // the Portrait quilt's 48 views of 420x560
  Daemon daemon(config, std::cerr);
  daemon.start();
  const auto stub = connect(files.socketAddress());
  v1::SceneHandle handle;
  ASSERT_TRUE(loadScene(*stub, "cube.obj", &handle).ok());

  ParityRunner runner(files, *stub);
  ParityCase c{"builtin:portrait", handle.scene_id(), (files.sceneRoot() / "cube.obj").string()};
  c.quiltPath = true;
  c.layouts = {"auto"};
  c.spp = 1;  // 11.3 M pixels: one sample (the seed's effect is covered by the small displays)
  runner.check(c);
  EXPECT_EQ(runner.compared(), 3u);  // portrait_auto_f0000_qs8x6a0.75.png + .json, portrait_auto_f0000.exr
  EXPECT_FALSE(filesWithStem(runner.cliDir(), "portrait_auto_f0000_qs8x6a0.75.png").empty());
}

}  // namespace
}  // namespace ht::server::test
