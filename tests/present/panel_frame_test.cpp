// panel_frame_test.cpp - the panel image of a rendered frame (present/panel_frame.h) is the 8-bit encoding of the
// frame's mosaic (frame_io/view_mosaic.h), the image the file sink writes as PNG: for one view, views stacked and a
// quilt, whichever way panelFrame gets there.
#include "present/panel_frame.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "camera_models/display_config.h"
#include "common/error.h"
#include "frame_io/pixel_encoding.h"
#include "frame_io/view_mosaic.h"

namespace ht::present {
namespace {

std::vector<float> randomPixels(std::size_t floats) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> value(-0.1f, 1.2f);
  std::vector<float> rgba(floats);
  for (float& v : rgba) v = value(rng);
  return rgba;
}

void expectTheMosaicsBytes(const frame_io::FrameImages& frame, const std::optional<QuiltLayout>& quilt) {
  DisplayConfig config;
  const PanelFrame panel = panelFrame(frame, {config, quilt});
  const frame_io::RgbaImage mosaic = frame_io::mosaicImage(frame, frame.views > 1 ? quilt : std::nullopt);
  EXPECT_EQ(panel.width, mosaic.width);
  EXPECT_EQ(panel.height, mosaic.height);
  EXPECT_EQ(panel.rgba, frame_io::encodeRgba8Srgb(mosaic.rgba));
}

TEST(PanelFrame, IsTheEightBitMosaicOfOneViewStackedViewsAndAQuilt) {
  const std::vector<float> one = randomPixels(7 * 5 * 4);
  expectTheMosaicsBytes({7, 5, 1, one}, std::nullopt);
  const QuiltLayout layout = makeQuiltLayout(3, 2, 21, 10, 1.4);
  expectTheMosaicsBytes({7, 5, 1, one}, layout);  // a one-view frame is itself, quilt or not
  const std::vector<float> six = randomPixels(6 * 7 * 5 * 4);
  expectTheMosaicsBytes({7, 5, 6, six}, std::nullopt);  // stacked
  expectTheMosaicsBytes({7, 5, 6, six}, layout);        // tiled
  const PanelFrame tiled = panelFrame({7, 5, 6, six}, {DisplayConfig{}, layout});
  EXPECT_EQ(tiled.width, 21u);
  EXPECT_EQ(tiled.height, 10u);
}

// A stream's RGBA8 bytes are the panel frame where the panel image is the frame itself (one view, views stacked), so
// the daemon copies them instead of encoding twice; a quilt is not.
TEST(PanelFrame, FromTheFramesRgba8BytesIsThePanelFrameWhereTheImageIsTheFrame) {
  const QuiltLayout layout = makeQuiltLayout(3, 2, 21, 10, 1.4);
  const std::vector<float> one = randomPixels(7 * 5 * 4), six = randomPixels(6 * 7 * 5 * 4);
  DisplayConfig config;
  for (const auto& [frame, quilt] : {std::pair{frame_io::FrameImages{7, 5, 1, one}, std::optional<QuiltLayout>{}},
                                     std::pair{frame_io::FrameImages{7, 5, 1, one}, std::optional(layout)},
                                     std::pair{frame_io::FrameImages{7, 5, 6, six}, std::optional<QuiltLayout>{}}}) {
    ASSERT_TRUE(panelImageIsTheFrame(frame, {config, quilt}));
    const PanelFrame copied = panelFrameFromRgba8(frame, frame_io::encodeRgba8Srgb(frame.rgba));
    const PanelFrame encoded = panelFrame(frame, {config, quilt});
    EXPECT_EQ(copied.width, encoded.width);
    EXPECT_EQ(copied.height, encoded.height);
    EXPECT_EQ(copied.rgba, encoded.rgba);
  }
  EXPECT_FALSE(panelImageIsTheFrame({7, 5, 6, six}, {config, layout}));
  EXPECT_THROW(panelFrameFromRgba8({7, 5, 1, one}, std::vector<std::uint8_t>(7 * 5 * 4 - 4)), IoError);
}

}  // namespace
}  // namespace ht::present
