// quilt_present_xvfb_test.cpp - existing quilt content on the Xvfb display sink (issue 18): a quilt PNG with a
// vendor-style name (written by `holotrace render --quilt` and renamed `hologram_qs5x9a1.5.png`, the way Looking Glass
// tools name their quilts) played through the daemon (LoadScene + Present) and through `holotrace show --scene`. Both
// put on the panel's monitor exactly the bytes of `holotrace interleave`'s panel PNG for the same display: one content
// path (frame_io/quilt_file.h) from quilt to panel.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "frame_io/atomic_output_file.h"
#include "frame_io/image_encoding.h"
#include "present/edid.h"
#include "present/xvfb_server.h"
#include "tests/cli/process_runner.h"
#include "tests/present/screen_check.h"
#include "tests/server/server_fixture.h"

namespace ht::present {
namespace {

namespace v1 = holotrace::v1;
namespace fs = std::filesystem;
using server::test::kTinyHeight;
using server::test::kTinyWidth;

const Rect kPanel{160, 0, kTinyWidth, kTinyHeight};
const std::string kQuiltName = "hologram_qs5x9a1.5.png";

std::unique_ptr<XvfbServer> startPanelServer() {
  auto xvfb = std::make_unique<XvfbServer>(256, kTinyHeight);
  xvfb->setEdid("screen", makeEdid("LKG-T0001"));
  xvfb->setMonitor("MAIN", {0, 0, 160, kTinyHeight}, {});
  xvfb->setMonitor("LKG-T", kPanel, {"screen"});
  return xvfb;
}

cli::test::ProcessResult holotrace(const std::vector<std::string>& args) {
  return cli::test::runProcess(HOLOTRACE_EXE, args);
}

// A daemon directory holding the vendor-named quilt below its scene root, and the panel PNG that `holotrace
// interleave` makes of it for the daemon's "tiny" display (returned as RGB bytes).
std::vector<std::uint8_t> writeQuiltAndInterleavedPanel(const server::test::DaemonFiles& files) {
  const fs::path work = files.dir.path / "work";
  fs::create_directories(work);
  // The tiny panel's calibration with a 5x9 quilt of 48x32 views (the 16" Gen2 tile count, small tiles).
  std::string json = server::test::tinyDisplayJson();
  json.replace(json.find("\"camera\": {"), 11,
               R"("camera": { "quilt": {"columns": 5, "rows": 9, "width": 240, "height": 288},)");
  server::test::writeText(work / "tiny-quilt.json", json);
  cli::test::ProcessResult r = holotrace({"render", "--display", work / "tiny-quilt.json", "--scene", "builtin:plain",
                                          "--quilt", "--layout", "quilt", "-o", work / "take.png"});
  EXPECT_EQ(r.exitCode, 0) << r.err << r.out;
  fs::rename(work / "take_qs5x9a1.5.png", files.sceneRoot() / kQuiltName);
  r = holotrace({"interleave", "--display", files.dir.path / "displays" / "tiny.json", "--quilt",
                 files.sceneRoot() / kQuiltName, "-o", work / "panel.png"});
  EXPECT_EQ(r.exitCode, 0) << r.err << r.out;
  std::vector<std::uint8_t> rgb = test::pngRgb(work / "panel.png");
  EXPECT_EQ(rgb.size(), std::size_t(kTinyWidth) * kTinyHeight * 3);
  EXPECT_GE(std::set<std::uint8_t>(rgb.begin(), rgb.end()).size(), 8u) << "a panel with content";
  return rgb;
}

void presentOnce(v1::Holotrace::Stub& stub, const std::string& sceneId) {
  grpc::ClientContext context;
  v1::PresentRequest request;
  *request.mutable_render() = server::test::tinyRequest(sceneId);
  auto reader = stub.Present(&context, request);
  v1::PresentProgress progress;
  std::uint32_t done = 0;
  while (reader->Read(&progress)) done = progress.frames_done();
  const grpc::Status status = reader->Finish();
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(done, 1u);
}

// One test for both players: the quilt render behind them is the slow part.
TEST(QuiltOnPanel, DaemonAndShowPutTheInterleavedPanelOnTheMonitor) {
  server::test::DaemonFiles files;
  const std::vector<std::uint8_t> expected = writeQuiltAndInterleavedPanel(files);
  ASSERT_FALSE(::testing::Test::HasFailure());
  {
    auto xvfb = startPanelServer();
    server::DaemonConfig config = files.config();
    config.present.mode = server::PresentConfig::Mode::List;
    config.present.panels = {server::PanelTarget{"tiny", std::nullopt, std::nullopt}};
    config.present.xDisplay = xvfb->display();
    server::Daemon daemon(config, std::cerr);
    daemon.start();
    auto stub = server::test::connect(files.socketAddress());
    v1::SceneHandle quilt;
    ASSERT_TRUE(server::test::loadScene(*stub, kQuiltName, &quilt).ok());
    EXPECT_EQ(quilt.triangles(), 0u);
    presentOnce(*stub, quilt.scene_id());
    EXPECT_EQ(test::screenMismatches(xvfb->connection(), kPanel, expected, std::chrono::seconds(20)), 0u);
    daemon.shutdown(std::chrono::milliseconds(0));
  }
  auto xvfb = startPanelServer();
  const fs::path log = files.dir.path / "work" / "show.log";
  const pid_t show = test::startProcess(HOLOTRACE_EXE,
                                        {"show", "--display", files.dir.path / "displays" / "tiny.json", "--scene",
                                         files.sceneRoot() / kQuiltName, "--x-display", xvfb->display()},
                                        log);
  EXPECT_EQ(test::screenMismatches(xvfb->connection(), kPanel, expected, std::chrono::seconds(60)), 0u)
      << test::readText(log);
  kill(show, SIGTERM);
  EXPECT_EQ(test::waitExit(show), 0) << test::readText(log);
  const std::string text = test::readText(log);
  EXPECT_NE(text.find("quilt 5x9 of 48x32 (layout from the file name) interleaved for 96x64"), std::string::npos)
      << text;
  EXPECT_NE(text.find("showing on monitor LKG-T 96x64+160+0"), std::string::npos) << text;
}

TEST(QuiltOnPanel, ShowRefusesAQuiltForAnotherPanelNamingTheValue) {
  server::test::DaemonFiles files;
  const fs::path wide = files.dir.path / "wide_qs5x9a1.777.png";
  const std::uint32_t w = 240, h = 288;
  const frame_io::OutputFile file{wide, frame_io::encodeImage({w, h, std::vector<float>(std::size_t(w) * h * 4, 0.5f)},
                                                              frame_io::ImageFormat::Png8Srgb)};
  frame_io::writeFilesAtomically({&file, 1});
  const cli::test::ProcessResult r = holotrace({"show", "--display", files.dir.path / "displays" / "tiny.json",
                                                "--scene", wide, "--x-display", ":9999", "--seconds", "1"});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("field 'quilt aspect' = 1.777"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace ht::present
