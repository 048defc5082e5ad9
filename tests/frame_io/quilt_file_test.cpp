// quilt_file_test.cpp - a quilt file's tile layout from options, the `_qs` name tag or holotrace's embedded metadata
// (in that order, name and metadata must agree), the refusals naming file and field, and a quilt file interleaved
// exactly as its pixels are by camera_models' interleaveQuilt.
#include "frame_io/quilt_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "camera_models/lenticular_params.h"
#include "common/error.h"
#include "frame_io/atomic_output_file.h"
#include "frame_io/image_encoding.h"
#include "frame_io/quilt_metadata.h"
#include "tests/common/temp_directory.h"

namespace ht::frame_io {
namespace {

using ::testing::HasSubstr;

// A 96x64 panel with the Portrait's phase rates: render aspect 1.5.
DisplayConfig smallPanel() {
  return parseDisplayConfig(R"({"name": "small", "calibration": {"pitch": 52.59, "slope": -7.21, "center": 0.40,
      "viewCone": 40, "invView": 1, "DPI": 324, "screenW": 96, "screenH": 64, "flipImageX": 0, "flipImageY": 0,
      "flipSubp": 0}})",
                            "small.json", "");
}

ImageHeader header(std::uint32_t w, std::uint32_t h, const std::string& description = "") {
  ImageHeader result;
  result.width = w;
  result.height = h;
  if (!description.empty()) result.attributes.emplace_back("ImageDescription", description);
  return result;
}

std::string metadata(std::uint32_t columns, std::uint32_t rows, double aspect) {
  return quiltMetadataJson(smallPanel(), makeQuiltLayout(columns, rows, columns * 8, rows * 6, aspect));
}

ConfigError layoutError(const ImageHeader& h, const std::string& name, const QuiltLayoutHints& hints = {}) {
  try {
    resolveQuiltLayout(h, name, hints, smallPanel());
  } catch (const ConfigError& e) { return e; }
  ADD_FAILURE() << "resolveQuiltLayout accepted " << name;
  return ConfigError("", "", "", "");
}

TEST(QuiltFileLayout, FromTheNameTagTheMetadataOrTheOptions) {
  const QuiltFileLayout named = resolveQuiltLayout(header(40, 18), "take_qs5x3a1.5.png", {}, smallPanel());
  EXPECT_EQ(named.source, "file name");
  EXPECT_EQ(named.layout.columns, 5u);
  EXPECT_EQ(named.layout.rows, 3u);
  EXPECT_EQ(named.layout.tileWidth, 8u);
  EXPECT_EQ(named.layout.tileHeight, 6u);
  EXPECT_DOUBLE_EQ(named.layout.aspect, 1.5);

  const QuiltFileLayout meta =
      resolveQuiltLayout(header(40, 18, metadata(5, 3, 1.25)), "renamed.png", {}, smallPanel());
  EXPECT_EQ(meta.source, "metadata");
  EXPECT_EQ(meta.layout.columns, 5u);
  EXPECT_DOUBLE_EQ(meta.layout.aspect, 1.25);

  // Options win over both; an aspect option alone keeps the tag's counts.
  QuiltLayoutHints hints;
  hints.columns = 4, hints.rows = 2;
  const QuiltFileLayout options =
      resolveQuiltLayout(header(40, 18, metadata(5, 3, 1.5)), "a_qs5x3a1.5.png", hints, smallPanel());
  EXPECT_EQ(options.source, "options");
  EXPECT_EQ(options.layout.columns, 4u);
  EXPECT_EQ(options.layout.tileWidth, 10u);
  QuiltLayoutHints aspectOnly;
  aspectOnly.aspect = 1.4;
  EXPECT_DOUBLE_EQ(resolveQuiltLayout(header(40, 18), "a_qs5x3a1.5.png", aspectOnly, smallPanel()).layout.aspect, 1.4);

  // The short Bridge tag has no aspect: the display's own (96/64) stands in, the metadata's when it has one.
  EXPECT_DOUBLE_EQ(resolveQuiltLayout(header(40, 18), "a_qs5x3.png", {}, smallPanel()).layout.aspect, 1.5);
  EXPECT_DOUBLE_EQ(
      resolveQuiltLayout(header(40, 18, metadata(5, 3, 1.25)), "a_qs5x3.png", {}, smallPanel()).layout.aspect, 1.25);
  // A vendor's own ImageDescription (not holotrace metadata) is ignored.
  EXPECT_EQ(
      resolveQuiltLayout(header(40, 18, "{\"app\": \"HoloPlay Studio\"}"), "a_qs5x3a1.5.png", {}, smallPanel()).source,
      "file name");
}

TEST(QuiltFileLayout, RefusalsNameTheFileAndTheField) {
  const ConfigError none = layoutError(header(40, 18), "holiday.png");
  EXPECT_EQ(none.file(), "holiday.png");
  EXPECT_EQ(none.field(), "quilt name");
  EXPECT_THAT(none.expected(), HasSubstr("--columns"));

  const ConfigError disagree = layoutError(header(40, 18, metadata(5, 3, 1.5)), "a_qs8x6a1.5.png");
  EXPECT_EQ(disagree.field(), "quilt name");
  EXPECT_EQ(disagree.value(), "8x6");
  EXPECT_THAT(disagree.expected(), HasSubstr("5x3"));

  EXPECT_EQ(layoutError(header(40, 18), "a_qs0x3a1.5.png").field(), "quilt name");  // a count of 0
  EXPECT_EQ(layoutError(header(40, 18, R"({"generator": "holotrace", "rows": 3, "aspect": 1.5})"), "a.png").field(),
            "ImageDescription.columns");
  EXPECT_EQ(layoutError(header(40, 18, R"({"generator": "holotrace", "columns": 5, "rows": 3, "aspect": -1})"), "a.png")
                .field(),
            "ImageDescription.aspect");
  ImageHeader multiView = header(40, 18);
  multiView.views = 3;
  EXPECT_EQ(layoutError(multiView, "a_qs5x3a1.5.exr").field(), "views");
  EXPECT_EQ(layoutError(header(4, 18), "a_qs5x3a1.5.png").field(), "quiltWidth");  // narrower than its columns

  QuiltLayoutHints half;
  half.columns = 4;
  EXPECT_THROW(resolveQuiltLayout(header(40, 18), "a_qs5x3a1.5.png", half, smallPanel()), UsageError);
}

// The file's pixels, decoded, give the same panel as interleaving them in memory; a quilt for another panel aspect
// is refused before its pixels are read.
TEST(QuiltFileInterleave, InterleavesTheDecodedQuiltAndRefusesOneThatDoesNotFit) {
  test::TempDirectory dir;
  const DisplayConfig display = smallPanel();
  const QuiltLayout layout = makeQuiltLayout(4, 3, 4 * 12, 3 * 8, 1.5);
  std::vector<float> rgba(std::size_t(layout.quiltWidth) * layout.quiltHeight * 4, 1.0f);
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    if (i % 4 != 3) rgba[i] = float((i * 37) % 256) / 255.0f;
  }
  const OutputFile file{dir.path() / "q_qs4x3a1.5.exr",
                        encodeImage({layout.quiltWidth, layout.quiltHeight, rgba}, ImageFormat::ExrFloat)};
  writeFilesAtomically({&file, 1});
  const InterleavedQuilt panel = interleaveQuiltFile(file.path, display, {}, QuiltViewFilter::CentredLerp, 2);
  EXPECT_EQ(panel.width, 96u);
  EXPECT_EQ(panel.height, 64u);
  const std::vector<float> want = interleaveQuilt(
      quiltImageViews(layout, rgba), makeLenticularParams(display, Bounds3{}), QuiltViewFilter::CentredLerp, 1);
  EXPECT_EQ(panel.rgba, want);

  const OutputFile wide{dir.path() / "q_qs4x3a1.777.exr", file.bytes};
  writeFilesAtomically({&wide, 1});
  try {
    interleaveQuiltFile(wide.path, display, {}, QuiltViewFilter::VendorLerp, 1);
    FAIL() << "a 16:9 quilt was interleaved for a 3:2 panel";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.field(), "quilt aspect");
    EXPECT_THAT(e.what(), HasSubstr("q_qs4x3a1.777.exr"));
  }
}

}  // namespace
}  // namespace ht::frame_io
