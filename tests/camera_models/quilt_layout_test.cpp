// Quilt names, tile layout and device defaults (docs/OPTICS.md §4.1, §4.2): name tags round-trip and malformed tags are
// ConfigErrors; view 0 is the bottom-left tile and views run left to right, then upward.
#include <string>

#include <gtest/gtest.h>

#include "camera_models/quilt_layout.h"
#include "camera_test_support.h"
#include "common/error.h"

namespace ht {
namespace {

TEST(QuiltLayout, NameRoundTrips) {
  for (double aspect : {0.75, 1.0, 16.0 / 9.0, 0.5625, 1.7777, 0.1 + 0.2}) {
    for (auto [cols, rows] : {std::pair{5u, 9u}, {8u, 6u}, {11u, 6u}, {1u, 1u}, {1024u, 1024u}}) {
      const std::string tag = formatQuiltName(cols, rows, aspect);
      const QuiltName parsed = parseQuiltName("hologram" + tag + ".png");
      EXPECT_EQ(parsed.columns, cols) << tag;
      EXPECT_EQ(parsed.rows, rows) << tag;
      ASSERT_TRUE(parsed.aspect.has_value()) << tag;
      EXPECT_EQ(*parsed.aspect, aspect) << tag;  // shortest exact form: bit-identical
    }
  }
  EXPECT_EQ(formatQuiltName(8, 6, 0.75), "_qs8x6a0.75");
}

TEST(QuiltLayout, ParsesVendorNames) {
  const QuiltName webxr = parseQuiltName("/media/quilts/hologram_qs5x9a0.75.png");
  EXPECT_EQ(webxr.columns, 5u);
  EXPECT_EQ(webxr.rows, 9u);
  EXPECT_DOUBLE_EQ(*webxr.aspect, 0.75);
  const QuiltName bridge = parseQuiltName("scene_qs8x13.jpg");  // bridge.js short form: no aspect
  EXPECT_EQ(bridge.columns, 8u);
  EXPECT_EQ(bridge.rows, 13u);
  EXPECT_FALSE(bridge.aspect.has_value());
  const QuiltName integerAspect = parseQuiltName("x_qs7x7a1.png");
  EXPECT_DOUBLE_EQ(*integerAspect.aspect, 1.0);
}

TEST(QuiltLayout, MalformedNamesRejected) {
  for (const std::string name :
       {"hologram.png", "_qs0x9a0.75", "_qs5x0a0.75", "_qs5x9a", "_qs5x9a0", "_qs5x9a0.0", "_qs5x9a1.2.3", "_qsx9a1",
        "_qs5xa1", "_qs1025x1a1", "_qs99999999999x1a1", "_qs5x9a.", "qs5x9a0.75"}) {
    try {
      parseQuiltName(name);
      ADD_FAILURE() << "accepted " << name;
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.field(), "quilt name");
      EXPECT_EQ(e.file(), name);
    }
  }
}

TEST(QuiltLayout, TilesFromBottomLeftRowMajor) {
  const QuiltLayout layout = makeQuiltLayout(5, 9, 4096, 4096, 0.75);
  EXPECT_EQ(layout.tileWidth, 819u);
  EXPECT_EQ(layout.tileHeight, 455u);
  EXPECT_EQ(quiltTileOrigin(layout, 0), glm::uvec2(0, 0));
  EXPECT_EQ(quiltTileOrigin(layout, 4), glm::uvec2(4 * 819, 0));  // last of the bottom row
  EXPECT_EQ(quiltTileOrigin(layout, 5), glm::uvec2(0, 455));      // next row up
  EXPECT_EQ(quiltTileOrigin(layout, 44), glm::uvec2(4 * 819, 8 * 455));
  for (std::uint32_t view = 0; view < layout.views(); ++view) {
    const glm::uvec2 origin = quiltTileOrigin(layout, view);
    for (glm::uvec2 inside : {glm::uvec2(0, 0), glm::uvec2(818, 454), glm::uvec2(17, 300)}) {
      const std::optional<QuiltTilePixel> back = quiltTilePixel(layout, origin + inside);
      ASSERT_TRUE(back.has_value());
      EXPECT_EQ(back->view, view);
      EXPECT_EQ(back->pixel, inside);
    }
    // GetQuiltCoordinates: tile uv (0,0) is the tile's lower-left corner in quilt uv; (1,1) its upper-right.
    const glm::dvec2 lower = quiltUV(layout, view, {0.0, 0.0}), upper = quiltUV(layout, view, {1.0, 1.0});
    EXPECT_NEAR(lower.x * 4096.0, origin.x, 1e-9);
    EXPECT_NEAR(lower.y * 4096.0, origin.y, 1e-9);
    EXPECT_NEAR((upper.x - lower.x) * 4096.0, 819.0, 1e-9);
    EXPECT_NEAR((upper.y - lower.y) * 4096.0, 455.0, 1e-9);
  }
  // 4096 - 5*819 = 1 unused column on the right, 4096 - 9*455 = 1 unused row on top.
  EXPECT_FALSE(quiltTilePixel(layout, {4095, 0}).has_value());
  EXPECT_FALSE(quiltTilePixel(layout, {0, 4095}).has_value());
}

TEST(QuiltLayout, BadLayoutsRejected) {
  EXPECT_THROW(makeQuiltLayout(0, 9, 4096, 4096, 0.75), ConfigError);
  EXPECT_THROW(makeQuiltLayout(5, 9, 4, 4096, 0.75), ConfigError);
  EXPECT_THROW(makeQuiltLayout(5, 9, 4096, 4096, 0.0), ConfigError);
  EXPECT_THROW(makeQuiltLayout(5, 9, 4096, 4096, std::nan("")), ConfigError);
}

TEST(QuiltLayout, DeviceDefaults) {
  struct Expected {
    const char* display;
    std::uint32_t columns, rows, size, tileWidth, tileHeight;
  };
  for (const Expected& e :
       {Expected{"portrait", 8, 6, 3360, 420, 560}, Expected{"go", 11, 6, 4092, 372, 682},
        Expected{"gen3-16-landscape", 7, 7, 6000, 857, 857}, Expected{"gen1-8.9", 5, 9, 4096, 819, 455}}) {
    const DisplayConfig config = builtinDisplay(e.display);
    const QuiltLayout layout = defaultQuiltLayout(config);
    EXPECT_EQ(layout.columns, e.columns) << e.display;
    EXPECT_EQ(layout.rows, e.rows) << e.display;
    EXPECT_EQ(layout.quiltWidth, e.size) << e.display;
    EXPECT_EQ(layout.quiltHeight, e.size) << e.display;
    EXPECT_EQ(layout.tileWidth, e.tileWidth) << e.display;
    EXPECT_EQ(layout.tileHeight, e.tileHeight) << e.display;
    EXPECT_DOUBLE_EQ(layout.aspect, double(config.calibration->screenW) / config.calibration->screenH);
  }
  const QuiltLayout eightK = defaultQuiltLayout(test::eightKDisplay(2));  // 32" Gen3 landscape
  EXPECT_EQ(eightK.columns, 7u);
  EXPECT_EQ(eightK.quiltWidth, 8190u);
  EXPECT_THROW(defaultQuiltLayout(builtinDisplay("holovizio-wall-70")), ConfigError);
}

// camera.quilt replaces the device default; bad sizes are refused naming the field.
TEST(QuiltLayout, ConfigQuiltSizeReplacesTheDeviceDefault) {
  auto config = [](const std::string& quilt) {
    return parseDisplayConfig(R"({"name": "q", "calibration": {"pitch": 52.59, "slope": -7.21, "center": 0.4,
        "viewCone": 40, "invView": 1, "DPI": 324, "screenW": 1536, "screenH": 2048, "flipImageX": 0, "flipImageY": 0,
        "flipSubp": 0}, "camera": {"quilt": )" +
                                  quilt + "}}",
                              "q.json", "");
  };
  const QuiltLayout small = defaultQuiltLayout(config(R"({"columns": 4, "rows": 3, "width": 200, "height": 150})"));
  EXPECT_EQ(small.columns, 4u);
  EXPECT_EQ(small.rows, 3u);
  EXPECT_EQ(small.tileWidth, 50u);
  EXPECT_EQ(small.tileHeight, 50u);
  EXPECT_DOUBLE_EQ(small.aspect, 0.75);
  for (const char* bad :
       {R"({"columns": 4, "rows": 3, "width": 3, "height": 150})",
        R"({"columns": 0, "rows": 3, "width": 200, "height": 150})", R"({"columns": 4, "rows": 3, "width": 200})",
        R"({"columns": 4, "rows": 3, "width": 200, "height": 150, "depth": 1})", "[4, 3]"}) {
    try {
      config(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const ConfigError& e) { EXPECT_NE(std::string(e.field()).find("quilt"), std::string::npos) << e.what(); }
  }
}

}  // namespace
}  // namespace ht
