// quilt_interleave_test.cpp - the quilt -> panel interleave: each subpixel shows the view its phase addresses, the
// three view filters blend the views as their formulas say, a quilt image's tiles are found bottom-left first and
// never bleed into each other, and quilts that cannot fit a display are refused with the field named.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_model.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/quilt_interleave.h"
#include "common/error.h"
#include "tests/camera_models/camera_test_support.h"

namespace ht::test {
namespace {

// A 96x64 panel with the Portrait's phase rates (the test panel of tests/server) and a BGR variant.
DisplayConfig rateTestPanel(bool bgr = false, bool flipX = false) {
  return parseDisplayConfig(std::string(R"({"name": "small", "calibration": {"pitch": 52.59, "slope": -7.21,
      "center": 0.40, "viewCone": 40, "invView": 1, "DPI": 324, "screenW": 96, "screenH": 64, "flipImageX": )") +
                                (flipX ? "1" : "0") + R"(, "flipImageY": 0, "flipSubp": )" + (bgr ? "1" : "0") + "}}",
                            "small.json", "");
}

// `views` tiles of w x h, one after the other; view i has the uniform value value(i) in R, G, B.
template <class Value>
std::vector<float> uniformViewStack(std::uint32_t w, std::uint32_t h, std::uint32_t views, Value value) {
  std::vector<float> rgba;
  for (std::uint32_t i = 0; i < views; ++i) {
    for (std::uint32_t p = 0; p < w * h; ++p) rgba.insert(rgba.end(), {value(i), value(i), value(i), 1.0f});
  }
  return rgba;
}

float panelAt(const std::vector<float>& panel, std::uint32_t w, std::uint32_t h, std::uint32_t x, std::uint32_t y,
              std::uint32_t c) {
  return panel[(std::size_t(h - 1 - y) * w + x) * 4 + c];  // row 0 = top, y from the bottom
}

TEST(QuiltInterleave, NearestFilterShowsTheViewThePhaseAddresses) {
  const DisplayConfig display = builtinDisplay("portrait");
  const gpu_shared::LenticularParams params = makeLenticularParams(display, Bounds3{});
  const std::uint32_t n = 48, tile = 4;
  const std::vector<float> views = uniformViewStack(tile, tile, n, [&](std::uint32_t i) { return (i + 0.5f) / n; });
  const std::vector<float> panel =
      interleaveQuilt(viewStackViews(tile, tile, n, views), params, QuiltViewFilter::Nearest);
  const auto w = static_cast<std::uint32_t>(params.panel.x), h = static_cast<std::uint32_t>(params.panel.y);
  ASSERT_EQ(panel.size(), std::size_t(w) * h * 4);
  std::size_t wrong = 0;
  for (std::uint32_t y = 0; y < h; y += 7) {
    for (std::uint32_t x = 0; x < w; x += 5) {
      for (std::uint32_t c = 0; c < 3; ++c) {
        const float t = gpu_shared::lenticular_view_phase(params, x, y, c, glm::vec2(0.5f));
        const std::uint32_t view = std::min(n - 1, static_cast<std::uint32_t>(t * float(n)));
        if (std::fabs(panelAt(panel, w, h, x, y, c) - (float(view) + 0.5f) / float(n)) > 1e-6f) ++wrong;
      }
    }
  }
  EXPECT_EQ(wrong, 0u);
}

// Views whose value is their index i: each filter's output is its blend formula evaluated at z = t N, exactly.
TEST(QuiltInterleave, FiltersBlendTheViewsAsTheirFormulasSay) {
  for (const bool bgr : {false, true}) {
    const DisplayConfig display = rateTestPanel(bgr);
    const gpu_shared::LenticularParams params = makeLenticularParams(display, Bounds3{});
    const std::uint32_t n = 12, tile = 3, w = 96, h = 64;
    const std::vector<float> views = uniformViewStack(tile, tile, n, [](std::uint32_t i) { return float(i); });
    const QuiltViews q = viewStackViews(tile, tile, n, views);
    const auto nearest = interleaveQuilt(q, params, QuiltViewFilter::Nearest, 2);
    const auto vendor = interleaveQuilt(q, params, QuiltViewFilter::VendorLerp, 2);
    const auto centred = interleaveQuilt(q, params, QuiltViewFilter::CentredLerp, 2);
    float maxError = 0.0f;
    for (std::uint32_t y = 0; y < h; ++y) {
      for (std::uint32_t x = 0; x < w; ++x) {
        for (std::uint32_t c = 0; c < 3; ++c) {
          // z in float, as the interleave computes it, so that floor() agrees at bin edges.
          const float z = gpu_shared::lenticular_view_phase(params, x, y, c, glm::vec2(0.5f)) * float(n);
          // Nearest: floor(z). Vendor: mix(floor(z), floor(z) + 1 clamped to N-1, fract(z)). Centred: the same on
          // z - 1/2, both views clamped to [0, N-1], i.e. clamp(z - 1/2, 0, N-1) for a linear ramp of views.
          const float wantNearest = std::floor(z);
          const float wantVendor = z < float(n - 1) ? z : float(n - 1);
          const float wantCentred = std::clamp(z - 0.5f, 0.0f, float(n - 1));
          maxError = std::max({maxError, std::fabs(panelAt(nearest, w, h, x, y, c) - wantNearest),
                               std::fabs(panelAt(vendor, w, h, x, y, c) - wantVendor),
                               std::fabs(panelAt(centred, w, h, x, y, c) - wantCentred)});
        }
      }
    }
    // a + (b - a) w in float with a, b < 12: a few ulps of 12.
    EXPECT_LT(maxError, 1e-5f) << (bgr ? "BGR panel" : "RGB panel");
  }
}

// A quilt image (3 x 2 tiles, view 0 bottom-left, rows stored top first) interleaves exactly like the same views as
// a stack; the unused remainder of the quilt ("view portion" < 1) is never read.
TEST(QuiltInterleave, QuiltImageTilesAreFoundFromTheBottomLeft) {
  const DisplayConfig display = rateTestPanel();
  const gpu_shared::LenticularParams params = makeLenticularParams(display, Bounds3{});
  const std::uint32_t tileW = 5, tileH = 4, cols = 3, rows = 2, n = cols * rows;
  const QuiltLayout layout = makeQuiltLayout(cols, rows, cols * tileW + 2, rows * tileH + 1, 1.5);
  // Each tile pixel holds a value unique to (view, x, y): a wrong tile or a flipped row shows.
  auto value = [&](std::uint32_t view, std::uint32_t x, std::uint32_t yFromBottom) {
    return float(view * 100 + yFromBottom * 10 + x);
  };
  std::vector<float> quilt(std::size_t(layout.quiltWidth) * layout.quiltHeight * 4, -1000.0f);
  std::vector<float> stack(std::size_t(tileW) * tileH * n * 4);
  for (std::uint32_t view = 0; view < n; ++view) {
    const glm::uvec2 origin = quiltTileOrigin(layout, view);  // from the bottom
    for (std::uint32_t y = 0; y < tileH; ++y) {
      for (std::uint32_t x = 0; x < tileW; ++x) {
        const std::size_t qRow = layout.quiltHeight - 1 - (origin.y + y);
        const std::size_t sRow = std::size_t(view) * tileH + tileH - 1 - y;
        for (std::uint32_t c = 0; c < 4; ++c) {
          quilt[(qRow * layout.quiltWidth + origin.x + x) * 4 + c] = value(view, x, y);
          stack[(sRow * tileW + x) * 4 + c] = value(view, x, y);
        }
      }
    }
  }
  for (QuiltViewFilter filter : {QuiltViewFilter::Nearest, QuiltViewFilter::VendorLerp, QuiltViewFilter::CentredLerp}) {
    const auto fromQuilt = interleaveQuilt(quiltImageViews(layout, quilt), params, filter, 1);
    const auto fromStack = interleaveQuilt(viewStackViews(tileW, tileH, n, stack), params, filter, 1);
    EXPECT_EQ(fromQuilt, fromStack) << quiltViewFilterName(filter);
    for (float v : fromQuilt) ASSERT_GE(v, 0.0f) << "read the quilt's unused remainder";
  }
}

// Neighbouring views of 0 and 1: nearest-view output is exactly 0 or 1 everywhere, so no sample took a pixel of the
// next tile (the vendor's GL sampler would blend across the tile border at the edge pixels).
TEST(QuiltInterleave, SamplesStayInsideTheirTile) {
  const DisplayConfig display = rateTestPanel(false, true);  // flipImageX mirrors u: edges on both sides are sampled
  const gpu_shared::LenticularParams params = makeLenticularParams(display, Bounds3{});
  const QuiltLayout layout = makeQuiltLayout(4, 3, 4 * 7, 3 * 5, 1.5);
  std::vector<float> quilt(std::size_t(layout.quiltWidth) * layout.quiltHeight * 4, 1.0f);
  for (std::uint32_t y = 0; y < layout.quiltHeight; ++y) {
    for (std::uint32_t x = 0; x < layout.quiltWidth; ++x) {
      const auto tile = quiltTilePixel(layout, {x, layout.quiltHeight - 1 - y});
      ASSERT_TRUE(tile);
      for (std::uint32_t c = 0; c < 3; ++c) {
        quilt[(std::size_t(y) * layout.quiltWidth + x) * 4 + c] = float(tile->view % 2);
      }
    }
  }
  const auto panel = interleaveQuilt(quiltImageViews(layout, quilt), params, QuiltViewFilter::Nearest, 2);
  for (std::size_t i = 0; i < panel.size(); ++i) ASSERT_TRUE(panel[i] == 0.0f || panel[i] == 1.0f) << "at " << i;
}

TEST(QuiltInterleave, FilterNamesReadBack) {
  for (QuiltViewFilter f : {QuiltViewFilter::Nearest, QuiltViewFilter::VendorLerp, QuiltViewFilter::CentredLerp}) {
    EXPECT_EQ(parseQuiltViewFilter(quiltViewFilterName(f)), f);
  }
  EXPECT_EQ(parseQuiltViewFilter("vendor"), QuiltViewFilter::VendorLerp);
  EXPECT_EQ(parseQuiltViewFilter("centered"), QuiltViewFilter::CentredLerp);
  try {
    parseQuiltViewFilter("gaussian");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("'gaussian'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("centred-lerp"), std::string::npos) << e.what();
  }
}

TEST(QuiltInterleave, ImagesOfTheWrongSizeAreErrors) {
  const std::vector<float> pixels(5 * 4 * 4, 0.0f);
  EXPECT_THROW(viewStackViews(5, 4, 2, pixels), Error);  // two views need twice the pixels
  EXPECT_THROW(quiltImageViews(makeQuiltLayout(2, 2, 6, 4, 1.0), pixels), Error);
  QuiltViews empty = viewStackViews(5, 4, 1, pixels);
  empty.tileTopLeft.clear();
  const auto params = makeLenticularParams(rateTestPanel(), Bounds3{});
  EXPECT_THROW(interleaveQuilt(empty, params, QuiltViewFilter::Nearest), Error);
  QuiltViews outside = viewStackViews(5, 4, 1, pixels);
  outside.tileTopLeft[0] = {1, 0};  // a 5-wide tile at x = 1 leaves a 5-wide image
  EXPECT_THROW(interleaveQuilt(outside, params, QuiltViewFilter::Nearest), Error);
}

ConfigError fitError(const QuiltLayout& layout, const DisplayConfig& display) {
  try {
    checkQuiltFitsDisplay(layout, display, "take_qs.png");
  } catch (const ConfigError& e) { return e; }
  ADD_FAILURE() << "checkQuiltFitsDisplay accepted the quilt";
  return ConfigError("", "", "", "");
}

TEST(QuiltInterleave, QuiltsThatCannotFitTheDisplayAreRefusedNamingTheField) {
  const DisplayConfig portrait = builtinDisplay("portrait");  // 1536x2048, aspect 0.75
  EXPECT_NO_THROW(checkQuiltFitsDisplay(makeQuiltLayout(8, 6, 3360, 3360, 0.75), portrait, "a_qs8x6a0.75.png"));
  // Quilt names carry the aspect rounded: 16" Gen3 landscape quilts say 1.777 for 3840/2160 = 1.7778.
  EXPECT_NO_THROW(checkQuiltFitsDisplay(makeQuiltLayout(7, 7, 5999, 5999, 1.777), builtinDisplay("gen3-16-landscape"),
                                        "b_qs7x7a1.777.png"));

  const ConfigError aspect = fitError(makeQuiltLayout(8, 6, 3360, 3360, 1.777), portrait);
  EXPECT_EQ(aspect.file(), "take_qs.png");
  EXPECT_EQ(aspect.field(), "quilt aspect");
  EXPECT_NE(aspect.expected().find("1536x2048"), std::string::npos) << aspect.what();
  EXPECT_EQ(fitError(makeQuiltLayout(1, 1, 420, 560, 0.75), portrait).field(), "quilt tiles");
  EXPECT_EQ(fitError(makeQuiltLayout(64, 65, 4096, 4096, 0.75), portrait).field(), "quilt tiles");  // 4160 views
  EXPECT_EQ(fitError(makeQuiltLayout(8, 6, 8, 100, 0.75), portrait).field(), "quilt size");         // 1-px tiles
  EXPECT_EQ(fitError(makeQuiltLayout(8, 6, 3360, 3360, 0.75), loadFixture("display_pinhole.json")).field(), "model");
}

}  // namespace
}  // namespace ht::test
