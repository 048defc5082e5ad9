// panel_sink_xvfb_test.cpp - the display sink against a real X server (a private Xvfb with two RandR monitors and a
// synthetic "LKG-P0001" EDID on the panel's output): monitor auto-selection, exact bytes on screen (== the file
// sink's PNG of the same frame), newest-frame-wins under fast submission, window geometry, re-attach after the
// monitor is removed and added again. Small screens keep it fast.
#include <gtest/gtest.h>

#include <random>
#include <thread>

#include "frame_io/frame_package.h"
#include "frame_io/image_reading.h"
#include "frame_io/pixel_encoding.h"
#include "present/edid.h"
#include "present/panel_sink.h"
#include "present/randr_reader.h"
#include "present/screen_capture.h"
#include "present/xvfb_server.h"

namespace ht::present {
namespace {

constexpr std::uint32_t kPanelW = 96, kPanelH = 128;
const Rect kMainRect{0, 0, 160, 128};
const Rect kPanelRect{160, 0, kPanelW, kPanelH};

// One Xvfb for the suite: MAIN 160x128 without outputs, LKG-P 96x128 on output "screen" carrying the LKG EDID.
class PanelSinkXvfb : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    xvfb_ = new XvfbServer(256, 128);
    xvfb_->setEdid("screen", makeEdid("LKG-P0001"));
    addMonitors();
  }
  static void TearDownTestSuite() {
    delete xvfb_;
    xvfb_ = nullptr;
  }
  static void addMonitors() {
    xvfb_->setMonitor("MAIN", kMainRect, {});
    xvfb_->setMonitor("LKG-P", kPanelRect, {"screen"});
  }

  static PanelSinkOptions options(PresentModeChoice mode = PresentModeChoice::Auto) {
    PanelSinkOptions o;
    o.xDisplay = xvfb_->display();
    o.panel = PanelRequest{kPanelW, kPanelH, std::nullopt, std::nullopt};
    o.presentMode = mode;
    o.retryInterval = std::chrono::milliseconds(50);
    o.recheckInterval = std::chrono::milliseconds(50);
    o.log = [](const std::string&) {};
    return o;
  }

  // Waits up to 10 s for `done` to hold on the sink's stats.
  template <typename Predicate>
  static PanelSinkStats waitFor(const PanelSink& sink, Predicate done) {
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    PanelSinkStats s = sink.stats();
    while (!done(s) && Clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      s = sink.stats();
    }
    return s;
  }

  // Pixels of the panel rectangle that differ from `rgb` (polls: the driver may finish the copy after present).
  static std::size_t mismatchesOnScreen(const std::vector<std::uint8_t>& rgb) {
    const auto deadline = Clock::now() + std::chrono::seconds(5);
    std::size_t bad = 0;
    do {
      auto screen = captureRgb(xvfb_->connection(), kPanelRect);
      bad = 0;
      for (std::size_t i = 0; i < rgb.size(); i += 3) {
        bad += screen[i] != rgb[i] || screen[i + 1] != rgb[i + 1] || screen[i + 2] != rgb[i + 2];
      }
      if (bad == 0) return 0;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    } while (Clock::now() < deadline);
    return bad;
  }

  static XvfbServer* xvfb_;
};
XvfbServer* PanelSinkXvfb::xvfb_ = nullptr;

// A frame of noise (every code of every channel hit): linear RGBA floats.
std::vector<float> noiseFrame(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-0.05f, 1.05f);  // includes out-of-range values that clamp
  std::vector<float> rgba(std::size_t(kPanelW) * kPanelH * 4);
  for (float& v : rgba) v = value(rng);
  return rgba;
}

DisplayConfig panelConfig() {
  DisplayConfig c;
  c.name = "xvfb-panel";
  return c;
}

// The RGB bytes of the PNG the file sink writes for `rgba`, read back through frame_io's reader.
std::vector<std::uint8_t> pngRgb(const std::vector<float>& rgba) {
  DisplayConfig config = panelConfig();
  frame_io::FrameImages frame{kPanelW, kPanelH, 1, rgba};
  frame_io::FramePackage package = frame_io::packageFrame(frame, {config, std::nullopt}, frame_io::ViewLayout::Auto,
                                                          frame_io::FrameFormat::Png, "panel.png");
  EXPECT_EQ(package.files.size(), 1u);
  frame_io::ImageFile png = frame_io::decodeImage(package.files[0].bytes, package.files[0].name);
  std::vector<std::uint8_t> rgb;
  for (std::size_t i = 0; i < png.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) rgb.push_back(frame_io::srgbEncode8(png.rgba[i + c]));
  }
  return rgb;
}

PanelFrame panelFrameOf(const std::vector<float>& rgba) {
  DisplayConfig config = panelConfig();
  return panelFrame(frame_io::FrameImages{kPanelW, kPanelH, 1, rgba}, {config, std::nullopt});
}

TEST_F(PanelSinkXvfb, SnapshotShowsBothMonitorsAndTheEdid) {
  RandrSnapshot s = readRandrSnapshot(xvfb_->connection());
  ASSERT_NE(s.output("screen"), nullptr);
  EXPECT_EQ(s.output("screen")->edidMonitorName, "LKG-P0001");
  bool main = false, panel = false;
  for (const RandrMonitor& m : s.monitors) {
    main |= m.name == "MAIN" && m.rect == kMainRect && m.outputs.empty();
    panel |= m.name == "LKG-P" && m.rect == kPanelRect && m.outputs == std::vector<std::string>{"screen"};
  }
  EXPECT_TRUE(main && panel) << describeMonitors(s);
}

TEST_F(PanelSinkXvfb, AutoSelectsThePanelAndShowsThePngBytesInAWindowOfItsSize) {
  PanelSink sink(options());
  auto rgba = noiseFrame(1);
  sink.submit(panelFrameOf(rgba));
  PanelSinkStats s = waitFor(sink, [](const PanelSinkStats& st) { return st.presented >= 1; });
  ASSERT_TRUE(s.attached) << s.lastError;
  ASSERT_TRUE(s.monitor);
  EXPECT_EQ(s.monitor->monitor, "LKG-P");
  EXPECT_EQ(s.monitor->rule, "EDID LKG");
  EXPECT_EQ(s.monitor->rect, kPanelRect);
  EXPECT_EQ(s.swapchain.width, kPanelW);
  EXPECT_EQ(s.swapchain.height, kPanelH);
  EXPECT_EQ(s.swapchain.presentMode, "MAILBOX");  // lavapipe offers it on Xvfb
  EXPECT_EQ(s.swapchain.transfer, "copy");
  EXPECT_EQ(mismatchesOnScreen(pngRgb(rgba)), 0u);
  // The window: exactly the monitor rectangle, override-redirect.
  XConnection x(xvfb_->display());
  xcb_window_t id = sink.windowId();
  XReply<xcb_get_geometry_reply_t> g(xcb_get_geometry_reply(x.get(), xcb_get_geometry(x.get(), id), nullptr));
  XReply<xcb_translate_coordinates_reply_t> t(
      xcb_translate_coordinates_reply(x.get(), xcb_translate_coordinates(x.get(), id, x.root(), 0, 0), nullptr));
  XReply<xcb_get_window_attributes_reply_t> a(
      xcb_get_window_attributes_reply(x.get(), xcb_get_window_attributes(x.get(), id), nullptr));
  ASSERT_TRUE(g && t && a);
  EXPECT_EQ((Rect{t->dst_x, t->dst_y, g->width, g->height}), kPanelRect);
  EXPECT_EQ(g->border_width, 0);
  EXPECT_TRUE(a->override_redirect);
  EXPECT_EQ(a->map_state, XCB_MAP_STATE_VIEWABLE);
}

TEST_F(PanelSinkXvfb, FifoShowsTheSameBytes) {
  PanelSink sink(options(PresentModeChoice::Fifo));
  auto rgba = noiseFrame(2);
  sink.submit(panelFrameOf(rgba));
  PanelSinkStats s = waitFor(sink, [](const PanelSinkStats& st) { return st.presented >= 1; });
  ASSERT_TRUE(s.attached) << s.lastError;
  EXPECT_EQ(s.swapchain.presentMode, "FIFO");
  EXPECT_EQ(mismatchesOnScreen(pngRgb(rgba)), 0u);
}

// The storage-write path (frame_transfer.h; a compute shader stores the pixels), forced because lavapipe's Xvfb surface
// offers TRANSFER_DST as well as STORAGE: the same bytes as the PNG, in MAILBOX and FIFO.
TEST_F(PanelSinkXvfb, StorageWriteShowsTheSameBytes) {
  for (PresentModeChoice mode : {PresentModeChoice::Auto, PresentModeChoice::Fifo}) {
    PanelSinkOptions o = options(mode);
    o.transfer = FrameTransferChoice::ForceStorageWrite;
    PanelSink sink(o);
    auto rgba = noiseFrame(mode == PresentModeChoice::Fifo ? 4 : 3);
    sink.submit(panelFrameOf(rgba));
    PanelSinkStats s = waitFor(sink, [](const PanelSinkStats& st) { return st.presented >= 1; });
    ASSERT_TRUE(s.attached) << s.lastError;
    EXPECT_EQ(s.swapchain.transfer, "storage write");
    EXPECT_EQ(mismatchesOnScreen(pngRgb(rgba)), 0u);
  }
}

TEST_F(PanelSinkXvfb, TwentyFastFramesLeaveTheNewestOnScreenAndCountDrops) {
  PanelSink sink(options());
  // Attach first with a frame of its own, so the 20 meet a running present thread.
  sink.submit(panelFrameOf(noiseFrame(99)));
  ASSERT_TRUE(waitFor(sink, [](const PanelSinkStats& st) { return st.presented >= 1; }).attached);
  std::vector<std::vector<float>> frames;
  std::vector<PanelFrame> panel;
  for (std::uint32_t i = 0; i < 20; ++i) {
    frames.push_back(noiseFrame(100 + i));
    panel.push_back(panelFrameOf(frames.back()));
  }
  // Hold the X server (a grab): the present thread blocks in its next X request (the RandR re-check every 50 ms, or
  // the present itself), so the 20 frames meet a busy present thread however fast this machine presents.
  XConnection grabber(xvfb_->display());
  xcb_grab_server(grabber.get());
  xcb_flush(grabber.get());
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  const PanelSinkStats before = sink.stats();
  std::uint64_t last = 0;
  const auto start = Clock::now();
  for (PanelFrame& f : panel) last = sink.submit(std::move(f));
  const auto submitTime = Clock::now() - start;
  xcb_ungrab_server(grabber.get());
  xcb_flush(grabber.get());
  EXPECT_LT(submitTime, std::chrono::milliseconds(50)) << "submit() must not wait for presentation";
  PanelSinkStats s = waitFor(sink, [&](const PanelSinkStats& st) { return st.lastPresentedSequence == last; });
  EXPECT_EQ(s.lastPresentedSequence, last);
  EXPECT_EQ(s.submitted, 21u);
  EXPECT_GE(s.dropped - before.dropped, 18u);  // at most one frame taken before the thread blocked, the 20th shown
  EXPECT_LE(s.presented - before.presented, 20u - (s.dropped - before.dropped) + 1u);  // +1: a possible re-show
  EXPECT_EQ(mismatchesOnScreen(pngRgb(frames.back())), 0u);
}

TEST_F(PanelSinkXvfb, MonitorRemovedAndAddedAgainReattachesAndShowsTheLastFrame) {
  PanelSink sink(options());
  auto rgba = noiseFrame(3);
  sink.submit(panelFrameOf(rgba));
  ASSERT_TRUE(waitFor(sink, [](const PanelSinkStats& st) { return st.presented >= 1; }).attached);
  xvfb_->deleteMonitor("LKG-P");
  PanelSinkStats gone = waitFor(sink, [](const PanelSinkStats& st) { return !st.attached; });
  xvfb_->setMonitor("LKG-P", kPanelRect, {"screen"});  // back, before the expectations (the suite shares the layout)
  EXPECT_FALSE(gone.attached);
  EXPECT_NE(gone.lastError.find("LKG"), std::string::npos) << gone.lastError;  // names the LKG monitor it now sees
  PanelSinkStats back =
      waitFor(sink, [](const PanelSinkStats& st) { return st.attachments >= 2 && st.presented >= 2; });
  EXPECT_TRUE(back.attached) << back.lastError;
  EXPECT_EQ(back.attachments, 2u);
  ASSERT_TRUE(back.monitor);
  EXPECT_EQ(back.monitor->rect, kPanelRect);
  EXPECT_EQ(mismatchesOnScreen(pngRgb(rgba)), 0u);
}

TEST_F(PanelSinkXvfb, AFrameOfAnotherSizeIsRefusedAndTheLastGoodOneStays) {
  PanelSink sink(options());
  auto rgba = noiseFrame(4);
  sink.submit(panelFrameOf(rgba));
  ASSERT_TRUE(waitFor(sink, [](const PanelSinkStats& st) { return st.presented >= 1; }).attached);
  PanelFrame wrong;
  wrong.width = 10;
  wrong.height = 10;
  wrong.rgba.assign(400, 255);
  sink.submit(std::move(wrong));
  PanelSinkStats s = waitFor(sink, [](const PanelSinkStats& st) { return !st.lastError.empty(); });
  EXPECT_NE(s.lastError.find("is 10x10, the panel 96x128+160+0; not shown"), std::string::npos) << s.lastError;
  EXPECT_TRUE(s.attached);
  EXPECT_EQ(s.attachments, 1u);
  EXPECT_EQ(mismatchesOnScreen(pngRgb(rgba)), 0u);
}

TEST_F(PanelSinkXvfb, NoPanelOfTheSizeNamesTheMonitorsFound) {
  PanelSinkOptions o = options();
  o.panel.screenWidth = 1536;
  o.panel.screenHeight = 2048;
  PanelSink sink(o);
  PanelSinkStats s = waitFor(sink, [](const PanelSinkStats& st) { return !st.lastError.empty(); });
  EXPECT_FALSE(s.attached);
  EXPECT_NE(s.lastError.find("LKG monitor LKG-P 96x128+160+0 is not the calibration's 1536x2048"), std::string::npos)
      << s.lastError;
  EXPECT_NE(s.lastError.find("MAIN 160x128+0+0"), std::string::npos) << s.lastError;
}

TEST_F(PanelSinkXvfb, NoXServerIsAnErrorNotACrash) {
  PanelSinkOptions o = options();
  o.xDisplay = ":9999";
  PanelSink sink(o);
  PanelSinkStats s = waitFor(sink, [](const PanelSinkStats& st) { return !st.lastError.empty(); });
  EXPECT_FALSE(s.attached);
  EXPECT_NE(s.lastError.find("cannot connect to X display ':9999'"), std::string::npos) << s.lastError;
}

}  // namespace
}  // namespace ht::present
