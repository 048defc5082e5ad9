// daemon_present_xvfb_test.cpp - holotraced's display sink on a private Xvfb: the daemon config's "present" gives
// the tiny display (96x64) a sink, the sink picks the LKG monitor, a Present call puts the frame on it and the bytes
// on screen equal the PNG that Capture writes for the same request; Status reports the sink; when the X server goes
// away the daemon keeps serving frames and the sink re-attaches when a server is back on that display.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include <unistd.h>

#include "../server/server_fixture.h"
#include "frame_io/image_reading.h"
#include "frame_io/pixel_encoding.h"
#include "present/edid.h"
#include "present/screen_capture.h"
#include "present/xvfb_server.h"

namespace ht::present {
namespace {

namespace v1 = holotrace::v1;
using server::test::DaemonFiles;

const Rect kTinyPanel{160, 0, server::test::kTinyWidth, server::test::kTinyHeight};

std::unique_ptr<XvfbServer> configurePanelServer(std::unique_ptr<XvfbServer> xvfb) {
  xvfb->setEdid("screen", makeEdid("LKG-T0001"));
  xvfb->setMonitor("MAIN", {0, 0, 160, server::test::kTinyHeight}, {});
  xvfb->setMonitor("LKG-T", kTinyPanel, {"screen"});
  return xvfb;
}

std::unique_ptr<XvfbServer> startPanelServer(const std::string& display = "") {
  auto xvfb = std::make_unique<XvfbServer>(256, server::test::kTinyHeight, display);
  return configurePanelServer(std::move(xvfb));
}

// A server whose display number the test may take again after killing it. -displayfd hands other tests' servers the
// lowest free number, so a killed server's low number is the next one given out: under ctest -j2 another Xvfb test
// can take it before the restart (a failure seen once here). Numbers from 300 + pid % 600 up are never handed out
// while the low ones are free.
std::unique_ptr<XvfbServer> startRestartablePanelServer() {
  const int first = 300 + static_cast<int>(getpid() % 600);
  for (int number = first; number < first + 20; ++number) {
    try {
      return startPanelServer(":" + std::to_string(number));
    } catch (const present::PresentError&) {  // in use: the next number
    }
  }
  return startPanelServer(":" + std::to_string(first + 20));  // the last try reports its error
}

v1::PanelStatus panelStatus(v1::Holotrace::Stub& stub) {
  grpc::ClientContext context;
  v1::StatusResponse response;
  EXPECT_TRUE(stub.Status(&context, v1::StatusRequest{}, &response).ok());
  return response.panels_size() == 1 ? response.panels(0) : v1::PanelStatus{};
}

template <typename Predicate>
v1::PanelStatus waitForPanel(v1::Holotrace::Stub& stub, Predicate done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  v1::PanelStatus s = panelStatus(stub);
  while (!done(s) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    s = panelStatus(stub);
  }
  return s;
}

grpc::Status presentOne(v1::Holotrace::Stub& stub, const v1::RenderRequest& render, v1::PresentProgress* last) {
  grpc::ClientContext context;
  v1::PresentRequest request;
  *request.mutable_render() = render;
  auto reader = stub.Present(&context, request);
  v1::PresentProgress progress;
  while (reader->Read(&progress)) *last = progress;
  return reader->Finish();
}

std::vector<std::uint8_t> rgbOfPng(const std::filesystem::path& file) {
  frame_io::ImageFile image = frame_io::readImageFile(file);
  std::vector<std::uint8_t> rgb;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) rgb.push_back(frame_io::srgbEncode8(image.rgba[i + c]));
  }
  return rgb;
}

std::size_t mismatches(const XConnection& x, const std::vector<std::uint8_t>& expected) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  std::size_t bad = expected.size();
  while (bad != 0 && std::chrono::steady_clock::now() < deadline) {
    auto screen = captureRgb(x, kTinyPanel);
    bad = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) bad += screen[i] != expected[i];
    if (bad) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return bad;
}

TEST(DaemonPresentXvfb, PresentShowsCapturesBytesStatusReportsAndXServerLossIsSurvived) {
  auto xvfb = startRestartablePanelServer();
  const std::string display = xvfb->display();
  DaemonFiles files;
  server::DaemonConfig config = files.config();
  config.present.mode = server::PresentConfig::Mode::List;
  config.present.panels = {server::PanelTarget{"tiny", std::nullopt, std::nullopt}};
  config.present.xDisplay = display;
  server::Daemon daemon(config, std::cerr);
  daemon.start();
  auto stub = server::test::connect(files.socketAddress());
  v1::SceneHandle scene;
  ASSERT_TRUE(server::test::loadScene(*stub, "builtin:plain", &scene).ok());
  const v1::RenderRequest render = server::test::tinyRequest(scene.scene_id());

  // The sink found the LKG monitor by itself.
  v1::PanelStatus s = waitForPanel(*stub, [](const v1::PanelStatus& p) { return p.attached(); });
  ASSERT_TRUE(s.attached()) << s.last_error();
  EXPECT_EQ(s.display_id(), "tiny");
  EXPECT_EQ(s.monitor(), "LKG-T");
  EXPECT_EQ(s.edid_name(), "LKG-T0001");
  EXPECT_EQ(s.geometry(), "96x64+160+0");
  EXPECT_EQ(s.present_mode(), "MAILBOX");
  EXPECT_EQ(s.x_display(), display);

  // Present one frame; the screen shows exactly the PNG Capture writes for the same request.
  v1::PresentProgress progress;
  ASSERT_TRUE(presentOne(*stub, render, &progress).ok());
  EXPECT_EQ(progress.frames_done(), 1u);
  std::vector<std::string> captured;
  ASSERT_TRUE(
      server::test::captureFrame(*stub, "panel", render, v1::CAPTURE_FORMAT_PNG, v1::CAPTURE_LAYOUT_AUTO, captured)
          .ok());
  ASSERT_EQ(captured.size(), 1u);
  EXPECT_EQ(mismatches(xvfb->connection(), rgbOfPng(files.outputRoot() / captured[0])), 0u);
  s = waitForPanel(*stub, [](const v1::PanelStatus& p) { return p.presented() >= 1; });
  EXPECT_GE(s.presented(), 1u);
  EXPECT_EQ(s.submitted(), 1u);
  EXPECT_GT(s.last_present_latency_ms(), 0.0);

  // A display without a sink is a bad request.
  v1::RenderRequest rig = render;
  rig.set_display_id("rig");
  grpc::Status noSink = presentOne(*stub, rig, &progress);
  EXPECT_EQ(noSink.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(noSink.error_message().find("has no panel sink"), std::string::npos) << noSink.error_message();

  // The X server goes away: the sink detaches and says why, frames are still served.
  xvfb.reset();
  s = waitForPanel(*stub, [](const v1::PanelStatus& p) { return !p.attached(); });
  EXPECT_FALSE(s.attached());
  EXPECT_FALSE(s.last_error().empty());
  EXPECT_TRUE(server::test::renderOne(*stub, render).ok());
  ASSERT_TRUE(presentOne(*stub, render, &progress).ok());  // accepted; shown when the panel is back

  // A server is back on the same display: the sink re-attaches and shows the newest frame again.
  xvfb = startPanelServer(display);
  s = waitForPanel(*stub, [](const v1::PanelStatus& p) { return p.attached() && p.attachments() >= 2; });
  EXPECT_TRUE(s.attached()) << s.last_error();
  EXPECT_EQ(s.attachments(), 2u);
  EXPECT_EQ(mismatches(xvfb->connection(), rgbOfPng(files.outputRoot() / captured[0])), 0u);
  daemon.shutdown(std::chrono::milliseconds(0));
}

// RGB of a PNG held in memory (a streamed PIXEL_FORMAT_PNG frame).
std::vector<std::uint8_t> rgbOfPngBytes(const std::vector<std::uint8_t>& png) {
  const auto file = std::filesystem::temp_directory_path() / ("ht_stream_" + std::to_string(getpid()) + ".png");
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  std::vector<std::uint8_t> rgb = rgbOfPng(file);
  std::filesystem::remove(file);
  return rgb;
}

// Streams `count` frames of `request` and cancels; returns the frames received and the final status.
grpc::Status streamFrames(v1::Holotrace::Stub& stub, const v1::StreamRequest& request, int count,
                          std::vector<server::test::ReceivedFrame>& frames) {
  grpc::ClientContext context;
  auto reader = stub.StreamFrames(&context, request);
  server::test::ReceivedFrame frame;
  bool open = true;
  while (static_cast<int>(frames.size()) < count && (open = server::test::readFrame(*reader, frame)))
    frames.push_back(frame);
  if (!open) return reader->Finish();  // refused or ended by the daemon
  context.TryCancel();
  while (server::test::readFrame(*reader, frame)) {}
  return reader->Finish();
}

// StreamFrames with present_on: every streamed frame also goes to the panel; the screen shows the last one's PNG
// bytes, and then an RGBA8 stream's last frame. An unknown id and a display without a sink are refused before any
// frame, naming it.
TEST(DaemonPresentXvfb, StreamFramesPresentOnShowsTheLastStreamedFrame) {
  auto xvfb = startPanelServer();
  DaemonFiles files;
  server::DaemonConfig config = files.config();
  config.present.mode = server::PresentConfig::Mode::List;
  config.present.panels = {server::PanelTarget{"tiny", std::nullopt, std::nullopt}};
  config.present.xDisplay = xvfb->display();
  server::Daemon daemon(config, std::cerr);
  daemon.start();
  auto stub = server::test::connect(files.socketAddress());
  v1::SceneHandle scene;
  ASSERT_TRUE(server::test::loadScene(*stub, "builtin:plain", &scene).ok());
  v1::StreamRequest request;
  *request.mutable_render() = server::test::tinyRequest(scene.scene_id(), v1::PIXEL_FORMAT_PNG);
  request.set_frames_per_second(4.0);  // slow: no third frame is rendered between the second and the cancel
  std::vector<server::test::ReceivedFrame> frames;

  request.set_present_on("nope");
  grpc::Status unknown = streamFrames(*stub, request, 1, frames);
  EXPECT_EQ(unknown.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(unknown.error_message().find("present_on: unknown display id 'nope'"), std::string::npos)
      << unknown.error_message();
  request.set_present_on("wall");
  grpc::Status noSink = streamFrames(*stub, request, 1, frames);
  EXPECT_EQ(noSink.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_NE(noSink.error_message().find("display 'wall' has no panel sink"), std::string::npos)
      << noSink.error_message();
  EXPECT_TRUE(frames.empty());

  ASSERT_TRUE(waitForPanel(*stub, [](const v1::PanelStatus& p) { return p.attached(); }).attached());
  request.set_present_on("tiny");
  EXPECT_EQ(streamFrames(*stub, request, 2, frames).error_code(), grpc::StatusCode::CANCELLED);
  ASSERT_EQ(frames.size(), 2u);
  const v1::PanelStatus s = waitForPanel(*stub, [](const v1::PanelStatus& p) { return p.submitted() >= 2; });
  EXPECT_EQ(s.submitted(), 2u);
  const std::vector<std::uint8_t> last = rgbOfPngBytes(frames[1].bytes);
  ASSERT_EQ(last.size(), std::size_t(server::test::kTinyWidth) * server::test::kTinyHeight * 3);
  EXPECT_EQ(mismatches(xvfb->connection(), last), 0u);

  // An RGBA8 stream (independent frames): the panel gets the streamed bytes themselves, encoded once for both.
  request.mutable_render()->set_format(v1::PIXEL_FORMAT_RGBA8);
  request.set_mode(v1::STREAM_MODE_INDEPENDENT);
  frames.clear();
  EXPECT_EQ(streamFrames(*stub, request, 2, frames).error_code(), grpc::StatusCode::CANCELLED);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(waitForPanel(*stub, [](const v1::PanelStatus& p) { return p.submitted() >= 4; }).submitted(), 4u);
  std::vector<std::uint8_t> rgb;
  for (std::size_t i = 0; i + 3 < frames[1].bytes.size(); i += 4) {
    rgb.insert(rgb.end(), frames[1].bytes.begin() + std::ptrdiff_t(i), frames[1].bytes.begin() + std::ptrdiff_t(i + 3));
  }
  ASSERT_EQ(rgb.size(), last.size());
  EXPECT_EQ(mismatches(xvfb->connection(), rgb), 0u);
  daemon.shutdown(std::chrono::milliseconds(0));
}

// display id -> status of every panel sink the daemon reports.
std::map<std::string, v1::PanelStatus> allPanels(v1::Holotrace::Stub& stub) {
  grpc::ClientContext context;
  v1::StatusResponse response;
  EXPECT_TRUE(stub.Status(&context, v1::StatusRequest{}, &response).ok());
  std::map<std::string, v1::PanelStatus> out;
  for (const v1::PanelStatus& p : response.panels()) out[p.display_id()] = p;
  return out;
}

template <typename Predicate>
std::map<std::string, v1::PanelStatus> waitForPanels(v1::Holotrace::Stub& stub, Predicate done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  auto panels = allPanels(stub);
  while (!done(panels) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    panels = allPanels(stub);
  }
  return panels;
}

bool attached(const std::map<std::string, v1::PanelStatus>& panels, const std::string& id) {
  auto it = panels.find(id);
  return it != panels.end() && it->second.attached();
}

// "present": "auto" and SIGHUP: a display config that appears in displays_dir (with a "panel" geometry) and a panel
// whose calibration appears (device pick-up) get sinks; when they are gone their sinks go; the running sink of the
// unchanged display keeps its window (one attachment) and its frames.
TEST(DaemonPresentXvfb, SighupAddsAndRemovesSinksWithoutDisturbingRunningOnes) {
  auto xvfb = startPanelServer();
  xvfb->setMonitor("LEFT", {0, 0, server::test::kTinyWidth, server::test::kTinyHeight}, {});
  DaemonFiles files;
  server::DaemonConfig config = files.config();
  const std::filesystem::path deviceFile = config.displaysDir.parent_path() / "panel-visual.json";
  config.present.mode = server::PresentConfig::Mode::Auto;
  config.present.xDisplay = xvfb->display();
  config.devices = server::DeviceDiscoveryConfig{true, deviceFile, false, false, false, {}, {}};
  server::Daemon daemon(config, std::cerr);
  daemon.start();
  auto stub = server::test::connect(files.socketAddress());
  v1::SceneHandle scene;
  ASSERT_TRUE(server::test::loadScene(*stub, "builtin:plain", &scene).ok());
  auto panels = waitForPanels(*stub, [](const auto& p) { return attached(p, "tiny"); });
  ASSERT_TRUE(attached(panels, "tiny"));
  EXPECT_EQ(panels.count("left"), 0u);
  v1::PresentProgress progress;
  ASSERT_TRUE(presentOne(*stub, server::test::tinyRequest(scene.scene_id()), &progress).ok());

  // A display config with a "panel" geometry and a plugged-in panel's calibration appear; SIGHUP.
  nlohmann::json left = nlohmann::json::parse(server::test::tinyDisplayJson());
  left["name"] = "left";
  left["panel"] = {{"geometry", "96x64+0+0"}};
  server::test::writeText(config.displaysDir / "left.json", left.dump());
  nlohmann::json visual = left["calibration"];
  visual["serial"] = "LKG-T0002";
  server::test::writeText(deviceFile, visual.dump());
  daemon.reloadDisplays();
  panels = waitForPanels(*stub, [](const auto& p) { return attached(p, "left") && attached(p, "device:LKG-T0002"); });
  ASSERT_TRUE(attached(panels, "left")) << panels["left"].last_error();
  EXPECT_EQ(panels["left"].monitor(), "LEFT");  // by the display config's geometry, before the EDID rule
  EXPECT_EQ(panels["left"].geometry(), "96x64+0+0");
  EXPECT_TRUE(attached(panels, "device:LKG-T0002")) << panels["device:LKG-T0002"].last_error();
  EXPECT_EQ(panels["device:LKG-T0002"].monitor(), "LKG-T");
  EXPECT_EQ(panels["tiny"].attachments(), 1u) << "the running sink was not restarted";
  EXPECT_EQ(panels["tiny"].submitted(), 1u);

  // Both are gone again; SIGHUP removes their sinks, the running one stays.
  std::filesystem::remove(config.displaysDir / "left.json");
  std::filesystem::remove(deviceFile);
  daemon.reloadDisplays();
  panels = allPanels(*stub);
  EXPECT_EQ(panels.count("left"), 0u);
  EXPECT_EQ(panels.count("device:LKG-T0002"), 0u);
  ASSERT_TRUE(attached(panels, "tiny"));
  EXPECT_EQ(panels["tiny"].attachments(), 1u);
  EXPECT_EQ(panels["tiny"].submitted(), 1u);
  daemon.shutdown(std::chrono::milliseconds(0));
}

}  // namespace
}  // namespace ht::present

namespace ht::server {
namespace {

PresentConfig presentOf(const std::string& json) { return parseDaemonConfig(json, "d.json", "/tmp").present; }

std::string configError(const std::string& json) {
  try {
    presentOf(json);
  } catch (const ConfigError& e) { return e.what(); }
  return "";
}

TEST(DaemonPresentConfig, ModesListsAndErrors) {
  const std::string roots = R"("scene_root": "s", "output_root": "o")";
  EXPECT_EQ(presentOf("{" + roots + "}").mode, PresentConfig::Mode::None);
  EXPECT_EQ(presentOf("{" + roots + R"(, "present": "none"})").mode, PresentConfig::Mode::None);
  EXPECT_EQ(presentOf("{" + roots + R"(, "present": "auto", "x_display": ":3"})").xDisplay, ":3");
  PresentConfig list = presentOf("{" + roots +
                                 R"(, "present": ["tiny", {"display": "go", "output": "HDMI-1"},
                                     {"display": "p2", "geometry": "1536x2048+1920+0"}]})");
  ASSERT_EQ(list.mode, PresentConfig::Mode::List);
  ASSERT_EQ(list.panels.size(), 3u);
  EXPECT_EQ(list.panels[1].output, "HDMI-1");
  EXPECT_EQ(list.panels[2].geometry, "1536x2048+1920+0");
  EXPECT_NE(configError("{" + roots + R"(, "present": "yes"})").find("field 'present'"), std::string::npos);
  EXPECT_NE(configError("{" + roots + R"(, "present": ["a", "a"]})").find("each display at most once"),
            std::string::npos);
  EXPECT_NE(configError("{" + roots + R"(, "present": [{"display": "a", "geometry": "big"}]})")
                .find("field 'present[0].geometry' = big"),
            std::string::npos);
  EXPECT_NE(configError("{" + roots + R"(, "present": [{"display": "a", "screen": 1}]})").find("present[0].screen"),
            std::string::npos);
  EXPECT_NE(configError("{" + roots + R"(, "present": [{"display": "a", "output": "X", "geometry": "1x1+0+0"}]})")
                .find("not both"),
            std::string::npos);
  EXPECT_NE(configError("{" + roots + R"(, "x_display": 0})").find("x_display"), std::string::npos);
}

TEST(DaemonPresentConfig, UnknownOrMultiViewDisplayIsRefusedAtStart) {
  test::DaemonFiles files;
  DaemonConfig config = files.config();
  config.present.mode = PresentConfig::Mode::List;
  config.present.panels = {PanelTarget{"nope", std::nullopt, std::nullopt}};
  try {
    Daemon daemon(config, std::cerr);
    FAIL() << "an unknown display in present must be refused";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'present' = nope"), std::string::npos) << e.what();
  }
  config.present.panels = {PanelTarget{"rig", std::nullopt, std::nullopt}};
  try {
    Daemon daemon(config, std::cerr);
    FAIL() << "a multi-view display in present must be refused";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("renders 6 views"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ht::server
