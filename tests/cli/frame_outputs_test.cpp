// frame_outputs_test.cpp - how multi-view frames are written: quilt tiling (view 0 bottom-left, rows from the top),
// the `_qs` file name, the quilt metadata, and the multiView EXR read back channel by channel.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "camera_models/quilt_layout.h"
#include "cli/frame_outputs.h"
#include "cli/image_file_writer.h"
#include "common/error.h"
#include "temp_directory.h"

namespace ht::cli {
namespace {

namespace fs = std::filesystem;

// views x (w x h) frame where every pixel encodes (view, x, row-from-top) in R, G, B.
gpu::RenderResult codedFrame(std::uint32_t views, std::uint32_t w, std::uint32_t h) {
  gpu::RenderResult frame;
  frame.width = w;
  frame.height = h;
  frame.views = views;
  for (std::uint32_t v = 0; v < views; ++v)
    for (std::uint32_t row = 0; row < h; ++row)
      for (std::uint32_t x = 0; x < w; ++x) frame.rgba.insert(frame.rgba.end(), {float(v), float(x), float(row), 1.0f});
  return frame;
}

TEST(FrameOutputs, QuiltPutsViewZeroBottomLeftAndKeepsRowsUpright) {
  const QuiltLayout layout = makeQuiltLayout(3, 2, 14, 9, 1.5);  // tiles 4x4, remainder 2 px right, 1 px top
  const gpu::RenderResult frame = codedFrame(6, 4, 4);
  const std::vector<float> quilt = gpu::assembleQuilt(frame, layout);
  ASSERT_EQ(quilt.size(), 14u * 9u * 4u);
  auto at = [&](std::uint32_t x, std::uint32_t rowFromTop, int c) { return quilt[(rowFromTop * 14 + x) * 4 + c]; };
  // Bottom-left tile = view 0: the quilt's bottom row is the view's bottom row (row 3 from its top).
  EXPECT_EQ(at(0, 8, 0), 0.0f);
  EXPECT_EQ(at(0, 8, 2), 3.0f);
  EXPECT_EQ(at(5, 8, 0), 1.0f);   // next tile to the right = view 1
  EXPECT_EQ(at(5, 8, 1), 1.0f);   // its x = 1
  EXPECT_EQ(at(0, 4, 0), 3.0f);   // second row of tiles (from the bottom) starts with view 3
  EXPECT_EQ(at(0, 1, 2), 0.0f);   // top row of view 3's tile is its row 0
  EXPECT_EQ(at(11, 1, 0), 5.0f);  // top-right used tile = last view
  // Unused remainder: opaque black.
  EXPECT_EQ(at(13, 4, 0), 0.0f);
  EXPECT_EQ(at(13, 4, 3), 1.0f);
  EXPECT_EQ(at(3, 0, 2), 0.0f);
}

TEST(FrameOutputs, QuiltLayoutMustMatchTheFrame) {
  const QuiltLayout layout = makeQuiltLayout(3, 2, 12, 8, 1.0);
  EXPECT_THROW(gpu::assembleQuilt(codedFrame(5, 4, 4), layout), IoError);
  EXPECT_THROW(gpu::assembleQuilt(codedFrame(6, 4, 3), layout), IoError);
}

TEST(FrameOutputs, QuiltFileNameGetsTheStandardTag) {
  const QuiltLayout layout = makeQuiltLayout(8, 6, 3360, 3360, 0.75);
  EXPECT_EQ(quiltFilePath("out/frame.png", layout), fs::path("out/frame_qs8x6a0.75.png"));
  EXPECT_EQ(quiltFilePath("out/mine_qs8x6a0.75.png", layout), fs::path("out/mine_qs8x6a0.75.png"));
  const QuiltName parsed = parseQuiltName(quiltFilePath("a/b.png", layout).filename().string());
  EXPECT_EQ(parsed.columns, 8u);
  EXPECT_EQ(parsed.rows, 6u);
  EXPECT_EQ(parsed.aspect, 0.75);
}

TEST(FrameOutputs, QuiltMetadataCarriesLayoutConeAndCalibrationVerbatim) {
  const DisplayConfig display = builtinDisplay("portrait");
  const gpu::DisplayCamera camera = gpu::makeDisplayCamera(display, Bounds3{}, gpu::CameraPath::Quilt);
  const nlohmann::json meta = nlohmann::json::parse(gpu::quiltMetadataJson(display, camera));
  EXPECT_EQ(meta["views"], 48);
  EXPECT_EQ(meta["columns"], 8);
  EXPECT_EQ(meta["rows"], 6);
  EXPECT_EQ(meta["aspect"], 0.75);
  EXPECT_EQ(meta["tileWidth"], 420);
  EXPECT_NEAR(meta["viewConeDeg"].get<double>(), display.calibration->viewCone * display.camera.depthiness, 1e-4);
  EXPECT_EQ(meta["calibration"], nlohmann::json::parse(display.calibration->rawJson));
}

TEST(FrameOutputs, MultiViewExrHoldsEveryViewUnderItsName) {
  test::TempDirectory dir;
  const gpu::RenderResult frame = codedFrame(3, 5, 2);
  const fs::path path = dir.path() / "views.exr";
  writeMultiViewExr(path, 5, 2, frame.rgba, {"view00", "view01", "view02"}, ImageFormat::ExrFloat);
  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  ASSERT_EQ(spec.nchannels, 12);
  EXPECT_EQ(spec.channelnames[4], "view01.R");
  const OIIO::ParamValue* views = spec.find_attribute("multiView");
  ASSERT_NE(views, nullptr);
  EXPECT_EQ(views->type().arraylen, 3);
  std::vector<float> pixels(5 * 2 * 12);
  ASSERT_TRUE(in->read_image(0, 0, 0, 12, OIIO::TypeDesc::FLOAT, pixels.data()));
  // Pixel (x = 3, row 1), view 2: R = view, G = x, B = row.
  const float* p = &pixels[(1 * 5 + 3) * 12 + 2 * 4];
  EXPECT_EQ(p[0], 2.0f);
  EXPECT_EQ(p[1], 3.0f);
  EXPECT_EQ(p[2], 1.0f);
}

TEST(FrameOutputs, MultiViewExrRejectsAMismatchedBuffer) {
  test::TempDirectory dir;
  const gpu::RenderResult frame = codedFrame(2, 4, 4);
  EXPECT_THROW(writeMultiViewExr(dir.path() / "x.exr", 4, 4, frame.rgba, {"a", "b", "c"}, ImageFormat::ExrHalf), IoError);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace ht::cli
