// frame_outputs_test.cpp - `holotrace render`'s output files: the packaged files land next to -o / --exr (which may
// be different directories), as one set, with one line each; a layout the display cannot take is a usage error.
#include "cli/frame_outputs.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "common/error.h"
#include "frame_io/image_reading.h"
#include "tests/common/temp_directory.h"

namespace ht::cli {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

gpu::RenderResult codedFrame(std::uint32_t views, std::uint32_t w, std::uint32_t h) {
  gpu::RenderResult frame;
  frame.width = w;
  frame.height = h;
  frame.views = views;
  for (std::uint32_t v = 0; v < views; ++v)
    for (std::uint32_t row = 0; row < h; ++row)
      for (std::uint32_t x = 0; x < w; ++x) frame.rgba.insert(frame.rgba.end(), {0.1f * float(v), 0.0f, 0.0f, 1.0f});
  return frame;
}

TEST(FrameOutputs, QuiltAndMultiViewExrGoNextToTheirPaths) {
  ht::test::TempDirectory dir;
  const DisplayConfig display = builtinDisplay("capture-8x6");
  const QuiltLayout layout = makeQuiltLayout(3, 2, 12, 8, 1.0);
  std::ostringstream out;
  writeFrameOutputs(out, {dir.path() / "png" / "cap.png", dir.path() / "exr" / "cap.exr"}, codedFrame(6, 4, 4),
                    {display, layout}, frame_io::ViewLayout::Auto);
  EXPECT_THAT(dir.entries(), ElementsAre("exr", "png"));
  EXPECT_TRUE(fs::is_regular_file(dir.path() / "png" / "cap_qs3x2a1.png"));
  EXPECT_TRUE(fs::is_regular_file(dir.path() / "png" / "cap_qs3x2a1.json"));
  const frame_io::ImageFile exr = frame_io::readImageFile(dir.path() / "exr" / "cap.exr");
  EXPECT_EQ(exr.views, 6u);
  EXPECT_THAT(out.str(), HasSubstr("wrote " + (dir.path() / "png" / "cap_qs3x2a1.png").string() +
                                   " + cap_qs3x2a1.json (quilt 3x2 of 4x4 tiles"));
  EXPECT_THAT(out.str(), HasSubstr("(6 views of 4x4, linear half EXR, multiView)"));
}

TEST(FrameOutputs, ViewsLayoutWritesOnePngPerView) {
  ht::test::TempDirectory dir;
  const DisplayConfig display = builtinDisplay("capture-8x6");
  std::ostringstream out;
  writeFrameOutputs(out, {dir.path() / "v.png", std::nullopt}, codedFrame(3, 2, 2), {display, std::nullopt},
                    frame_io::ViewLayout::Views);
  EXPECT_THAT(dir.entries(), ElementsAre("v_v00.png", "v_v01.png", "v_v02.png"));
  EXPECT_THAT(out.str(), HasSubstr("v_v00.png ... v_v02.png (3 views of 2x2, 8-bit sRGB PNG each)"));
}

TEST(FrameOutputs, QuiltLayoutOfAProjectorArrayIsAUsageErrorAndWritesNothing) {
  ht::test::TempDirectory dir;
  const DisplayConfig display = builtinDisplay("holovizio-wall-70");
  const frame_io::FrameDisplay wall{display, std::nullopt};
  EXPECT_NO_THROW(checkViewLayout(wall, 1, frame_io::ViewLayout::Quilt));
  try {
    checkViewLayout(wall, 70, frame_io::ViewLayout::Quilt);
    FAIL() << "expected UsageError";
  } catch (const UsageError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--layout quilt"));
    EXPECT_THAT(e.what(), HasSubstr("projector-array"));
  }
  std::ostringstream out;
  EXPECT_THROW(writeFrameOutputs(out, {dir.path() / "w.png", dir.path() / "w.exr"}, codedFrame(3, 2, 2), wall,
                                 frame_io::ViewLayout::Quilt),
               UsageError);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace ht::cli
