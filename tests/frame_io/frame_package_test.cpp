// frame_package_test.cpp - how frames become files: quilt tiling (view 0 bottom-left, rows from the top), file names
// (`_qs` tag, `_vNN`), quilt metadata embedded and as sidecar, multiView EXR view names, layout refusals, and the
// streamed mosaic PNG being the captured quilt's bytes.
#include "frame_io/frame_package.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "coded_views.h"
#include "common/error.h"
#include "frame_io/frame_file_names.h"
#include "frame_io/image_reading.h"
#include "frame_io/quilt_metadata.h"
#include "frame_io/view_mosaic.h"

namespace ht::frame_io {
namespace {

using ::testing::ElementsAre;

using test::codedViews;

std::vector<std::string> names(const FramePackage& package) {
  std::vector<std::string> out;
  for (const FrameFile& file : package.files) out.push_back(file.name);
  return out;
}

DisplayConfig captureGrid() { return builtinDisplay("capture-8x6"); }

TEST(ViewMosaic, QuiltPutsViewZeroBottomLeftAndKeepsRowsUpright) {
  const QuiltLayout layout = makeQuiltLayout(3, 2, 14, 9, 1.5);  // tiles 4x4, remainder 2 px right, 1 px top
  const std::vector<float> rgba = codedViews(6, 4, 4);
  const RgbaImage quilt = assembleQuilt({4, 4, 6, rgba}, layout);
  ASSERT_EQ(quilt.rgba.size(), 14u * 9u * 4u);
  auto at = [&](std::uint32_t x, std::uint32_t rowFromTop, int c) { return quilt.rgba[(rowFromTop * 14 + x) * 4 + c]; };
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

TEST(ViewMosaic, QuiltLayoutMustMatchTheFrameAndStackingKeepsViewZeroOnTop) {
  const QuiltLayout layout = makeQuiltLayout(3, 2, 12, 8, 1.0);
  EXPECT_THROW(assembleQuilt({4, 4, 5, codedViews(5, 4, 4)}, layout), IoError);
  EXPECT_THROW(assembleQuilt({4, 3, 6, codedViews(6, 4, 3)}, layout), IoError);
  const std::vector<float> rgba = codedViews(3, 2, 2);
  const RgbaImage stacked = mosaicImage({2, 2, 3, rgba}, std::nullopt);
  EXPECT_EQ(stacked.width, 2u);
  EXPECT_EQ(stacked.height, 6u);
  EXPECT_EQ(stacked.rgba, rgba);
}

TEST(FrameFileNames, QuiltTagViewNumbersAndSuffixes) {
  const QuiltLayout layout = makeQuiltLayout(8, 6, 3360, 3360, 0.75);
  EXPECT_EQ(quiltFileName("frame.png", layout), "frame_qs8x6a0.75.png");
  EXPECT_EQ(quiltFileName("mine_qs8x6a0.75.png", layout), "mine_qs8x6a0.75.png");  // already states this layout
  EXPECT_EQ(quiltFileName("old_qs5x9a0.75.png", layout), "old_qs5x9a0.75_qs8x6a0.75.png");  // the last tag wins
  EXPECT_EQ(quiltFileName("a_qsx.PNG", layout), "a_qsx_qs8x6a0.75.PNG");
  const QuiltName parsed = parseQuiltName(quiltFileName("b.png", layout));
  EXPECT_EQ(parsed.columns, 8u);
  EXPECT_EQ(parsed.rows, 6u);
  EXPECT_EQ(parsed.aspect, 0.75);
  EXPECT_EQ(viewNumber(3, 6), "03");
  EXPECT_EQ(viewNumber(7, 101), "007");
  EXPECT_EQ(multiViewName(69, 70), "view69");
  EXPECT_EQ(withSuffix("shot.png", "_v00"), "shot_v00.png");
  EXPECT_EQ(withExtension("shot_qs3x2a1.5.png", ".json"), "shot_qs3x2a1.5.json");
}

TEST(QuiltMetadata, CarriesLayoutConeAndCalibrationVerbatim) {
  const DisplayConfig display = builtinDisplay("portrait");
  const nlohmann::json meta = nlohmann::json::parse(quiltMetadataJson(display, defaultQuiltLayout(display)));
  EXPECT_EQ(meta["views"], 48);
  EXPECT_EQ(meta["columns"], 8);
  EXPECT_EQ(meta["rows"], 6);
  EXPECT_EQ(meta["aspect"], 0.75);
  EXPECT_EQ(meta["tileWidth"], 420);
  EXPECT_NEAR(meta["viewConeDeg"].get<double>(), display.calibration->viewCone * display.camera.depthiness, 1e-4);
  EXPECT_EQ(meta["calibration"], nlohmann::json::parse(display.calibration->rawJson));
  const DisplayConfig grid = captureGrid();
  const nlohmann::json gridMeta = nlohmann::json::parse(quiltMetadataJson(grid, makeQuiltLayout(8, 6, 80, 60, 1.0)));
  EXPECT_FALSE(gridMeta.contains("viewConeDeg"));
  EXPECT_EQ(gridMeta["model"], "capture-grid");
}

TEST(PackageFrame, OneViewIsOneFileInEitherFormat) {
  const DisplayConfig display = builtinDisplay("portrait");
  const std::vector<float> rgba = codedViews(1, 3, 2);
  const FramePackage png =
      packageFrame({3, 2, 1, rgba}, {display, std::nullopt}, ViewLayout::Quilt, FrameFormat::Png, "x.png");
  EXPECT_THAT(names(png), ElementsAre("x.png"));
  const FramePackage exr =
      packageFrame({3, 2, 1, rgba}, {display, std::nullopt}, ViewLayout::Views, FrameFormat::Exr, "x.exr");
  EXPECT_THAT(names(exr), ElementsAre("x.exr"));
  EXPECT_EQ(decodeImage(exr.files[0].bytes, "x.exr").channelTypes.front(), SampleType::Half);
}

TEST(PackageFrame, QuiltWithEmbeddedMetadataAndSidecarThenViewsThenMultiViewExr) {
  const DisplayConfig display = captureGrid();
  const QuiltLayout layout = makeQuiltLayout(3, 2, 12, 8, 1.0);
  const std::vector<float> rgba = codedViews(6, 4, 4);
  const FrameImages frame{4, 4, 6, rgba};
  const FrameDisplay withQuilt{display, layout};
  const FramePackage quilt = packageFrame(frame, withQuilt, ViewLayout::Auto, FrameFormat::Png, "s_f0000.png");
  ASSERT_THAT(names(quilt), ElementsAre("s_f0000_qs3x2a1.png", "s_f0000_qs3x2a1.json"));
  const std::string sidecar(quilt.files[1].bytes.begin(), quilt.files[1].bytes.end());
  EXPECT_EQ(sidecar, quiltMetadataJson(display, layout) + "\n");
  const ImageFile image = decodeImage(quilt.files[0].bytes, "q.png");
  EXPECT_EQ(image.attribute("ImageDescription") + "\n", sidecar);
  EXPECT_EQ(image.width, 12u);
  EXPECT_EQ(packageFrame(frame, withQuilt, ViewLayout::Quilt, FrameFormat::Png, "s_f0000.png").files[0].bytes,
            quilt.files[0].bytes);

  const FramePackage views = packageFrame(frame, withQuilt, ViewLayout::Views, FrameFormat::Png, "s.png");
  EXPECT_THAT(names(views), ElementsAre("s_v00.png", "s_v01.png", "s_v02.png", "s_v03.png", "s_v04.png", "s_v05.png"));
  EXPECT_EQ(decodeImage(views.files[0].bytes, "v0.png").rgba[0], 0.0f);  // R = view index, clamped to 1
  EXPECT_EQ(decodeImage(views.files[2].bytes, "v2.png").rgba[0], 1.0f);

  const FramePackage exr = packageFrame(frame, withQuilt, ViewLayout::Quilt, FrameFormat::Exr, "s.exr");
  ASSERT_THAT(names(exr), ElementsAre("s.exr"));
  const ImageFile back = decodeImage(exr.files[0].bytes, "s.exr");
  EXPECT_THAT(back.viewNames, ElementsAre("view00", "view01", "view02", "view03", "view04", "view05"));
}

TEST(PackageFrame, QuiltLayoutOfViewsThatFormNoQuiltIsRefusedInEveryFormat) {
  const DisplayConfig display = builtinDisplay("holovizio-wall-70");
  const std::vector<float> rgba = codedViews(3, 2, 2);
  const FrameDisplay noQuilt{display, std::nullopt};
  EXPECT_FALSE(layoutAllowed(noQuilt, 3, ViewLayout::Quilt));
  EXPECT_TRUE(layoutAllowed(noQuilt, 1, ViewLayout::Quilt));
  EXPECT_TRUE(layoutAllowed(noQuilt, 3, ViewLayout::Auto));
  for (FrameFormat format : {FrameFormat::Png, FrameFormat::Exr}) {
    EXPECT_THROW(packageFrame({2, 2, 3, rgba}, noQuilt, ViewLayout::Quilt, format, "w.png"), UsageError);
  }
  EXPECT_THAT(names(packageFrame({2, 2, 3, rgba}, noQuilt, ViewLayout::Auto, FrameFormat::Png, "w.png")),
              ElementsAre("w_v00.png", "w_v01.png", "w_v02.png"));
  EXPECT_THROW(packageFrame({2, 2, 4, rgba}, noQuilt, ViewLayout::Auto, FrameFormat::Png, "w.png"), IoError);
}

TEST(PackageFrame, MosaicPngIsTheQuiltFileOrTheStackedViews) {
  const DisplayConfig display = captureGrid();
  const QuiltLayout layout = makeQuiltLayout(3, 2, 12, 8, 1.0);
  const std::vector<float> rgba = codedViews(6, 4, 4);
  const FrameImages frame{4, 4, 6, rgba};
  const MosaicPng quilt = encodeMosaicPng(frame, {display, layout});
  EXPECT_EQ(quilt.width, 12u);
  EXPECT_EQ(quilt.height, 8u);
  EXPECT_EQ(quilt.bytes,
            packageFrame(frame, {display, layout}, ViewLayout::Auto, FrameFormat::Png, "a.png").files[0].bytes);
  const MosaicPng stacked = encodeMosaicPng(frame, {display, std::nullopt});
  EXPECT_EQ(stacked.width, 4u);
  EXPECT_EQ(stacked.height, 24u);
  const MosaicPng one = encodeMosaicPng({4, 4, 1, std::span<const float>(rgba).first(64)}, {display, layout});
  EXPECT_EQ(one.bytes, packageFrame({4, 4, 1, std::span<const float>(rgba).first(64)}, {display, layout},
                                    ViewLayout::Auto, FrameFormat::Png, "b.png")
                           .files[0]
                           .bytes);
}

}  // namespace
}  // namespace ht::frame_io
