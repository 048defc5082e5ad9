// The building blocks of holotrace-bench-quality and -traversal, checked against values worked out by hand: image
// metrics of known errors and Embree's tree holding every triangle exactly once with bounds that contain it (the
// quilt interleave moved to camera_models: tests/camera_models/quilt_interleave_test.cpp).
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "bench/embree_bvh_build.h"
#include "bench/image_metrics.h"
#include "bench/quality_points.h"
#include "common/error.h"
#include "scene/scene.h"

namespace ht::bench {
namespace {

std::vector<float> uniformImage(std::uint32_t w, std::uint32_t h, float value) {
  std::vector<float> rgba(std::size_t(w) * h * 4, value);
  for (std::size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 1.0f;
  return rgba;
}

TEST(ImageMetrics, IdenticalImagesHaveZeroErrorAndUnitSsim) {
  const std::vector<float> a = uniformImage(16, 12, 0.3f);
  const ImageMetrics m = compareImages(a, a, 16, 12);
  EXPECT_EQ(m.mse, 0.0);
  EXPECT_TRUE(std::isinf(m.psnrDb));
  EXPECT_NEAR(m.ssim, 1.0, 1e-12);
}

TEST(ImageMetrics, AKnownDisplayReferredErrorGivesItsPsnr) {
  // Linear value whose sRGB encoding is 0.1 (IEC 61966-2-1: V = ((E + 0.055)/1.055)^2.4 above 0.04045) vs black:
  // MSE = 0.01 on the display scale -> 20 dB.
  const float linear = float(std::pow((0.1 + 0.055) / 1.055, 2.4));
  const ImageMetrics m = compareImages(uniformImage(16, 12, linear), uniformImage(16, 12, 0.0f), 16, 12);
  EXPECT_NEAR(m.mse, 0.01, 1e-6);
  EXPECT_NEAR(m.psnrDb, 20.0, 1e-3);
  EXPECT_THROW(compareImages(uniformImage(16, 12, 0.0f), uniformImage(16, 11, 0.0f), 16, 12), Error);
}

QualityPoint point(const char* path, std::uint32_t spp, double ms, double psnr, std::uint32_t refineSpp = 0) {
  QualityPoint p;
  p.path = path;
  p.spp = spp;
  p.renderMs = ms;
  p.psnrCorrectedDb = psnr;
  p.refineSpp = refineSpp;
  return p;
}

// Equal-time / equal-PSNR comparisons worked by hand: the direct curve (1 s, 40 dB) -> (2 s, 44 dB); the adaptive
// curve keeps, of the adaptive and direct points, those better than every faster one: (1 s, 40) -> (1.5 s, 45)
// -> (4 s, 47); (1.8 s, 44) and (2 s, 44) are dominated.
TEST(ImageMetrics, ChangedValueFractionCountsColourValuesThatDifferAndSkipsAlpha) {
  std::vector<float> a = uniformImage(4, 2, 0.5f), b = a;
  EXPECT_EQ(changedValueFraction(a, b), 0.0);
  b[3] = 0.25f;  // alpha of pixel 0: not a colour value
  EXPECT_EQ(changedValueFraction(a, b), 0.0);
  b[0] = 0.25f;                               // red of pixel 0
  b[4 * 5 + 2] = std::nextafter(0.5f, 1.0f);  // blue of pixel 5, one ulp off
  EXPECT_DOUBLE_EQ(changedValueFraction(a, b), 2.0 / 24.0);
  EXPECT_THROW(changedValueFraction(a, uniformImage(4, 1, 0.5f)), Error);
}

TEST(QualityComparison, DirectAndAdaptiveCurvesAgainstAQuiltPoint) {
  DisplayQuality d;
  d.points = {point("direct", 1, 1000, 40),      point("direct", 2, 2000, 44),
              point("adaptive", 1, 1800, 44, 4), point("adaptive", 1, 1500, 45, 8),
              point("direct", 4, 4000, 47),      point("quilt", 1, std::sqrt(2.0) * 1000, 41)};
  const auto comparisons = d.compare();
  ASSERT_EQ(comparisons.size(), 1u);
  const EqualComparison& c = comparisons[0];
  ASSERT_TRUE(c.directGainDb && c.speedup && c.adaptiveGainDb && c.adaptiveSpeedup);
  EXPECT_NEAR(*c.directGainDb, 42.0 - 41.0, 1e-9);                  // half way in log2 time
  EXPECT_NEAR(*c.speedup, std::sqrt(2.0) / std::exp2(0.25), 1e-9);  // 41 dB a quarter of the way
  const double w = 0.5 / std::log2(1.5);                            // sqrt 2 s between 1 s and 1.5 s in log2 time
  EXPECT_NEAR(*c.adaptiveGainDb, 40.0 + 5.0 * w - 41.0, 1e-9);
  EXPECT_NEAR(*c.adaptiveSpeedup, std::sqrt(2.0) / std::exp2(std::log2(1.5) * 0.2), 1e-9);
  d.points.back() = point("quilt", 1, 3000, 46);  // between 1.5 s and 4 s: the adaptive curve, then direct spp 4
  const double w3 = std::log2(3000.0 / 1500.0) / std::log2(4000.0 / 1500.0);
  EXPECT_NEAR(*d.compare()[0].adaptiveGainDb, 45.0 + 2.0 * w3 - 46.0, 1e-9);
  d.points.back() = point("quilt", 1, 5000, 41);  // slower than every point: no equal-time figure
  EXPECT_FALSE(d.compare()[0].adaptiveGainDb.has_value());
  EXPECT_FALSE(d.compare()[0].directGainDb.has_value());
}

// Two timing runs, the second on a host twice as slow for the quilt: each point's time is the median of its same-run
// ratios to the quilt times the quilt's median (1500 ms), and each run is also compared on its own.
TEST(QualityComparison, SeveralRunsUseSameRunRatiosToTheQuilt) {
  DisplayQuality d;
  d.runs = 2;
  d.points = {point("direct", 1, 500, 40), point("adaptive", 1, 900, 45, 4), point("quilt", 1, 1000, 41)};
  d.points[0].runMs = {500, 1000};  // ratios 0.5, 0.5 -> 750 ms
  d.points[1].runMs = {900, 2200};  // ratios 0.9, 1.1 -> 1500 ms, the quilt's time
  d.points[2].runMs = {1000, 2000};
  EXPECT_DOUBLE_EQ(d.points[1].frameMs(), 1550.0);  // its own median
  EXPECT_DOUBLE_EQ(d.points[2].frameMs(), 1500.0);
  const auto comparisons = d.compare();
  ASSERT_EQ(comparisons.size(), 1u);
  const EqualComparison& c = comparisons[0];
  ASSERT_TRUE(c.adaptiveGainDb.has_value());
  EXPECT_NEAR(*c.adaptiveGainDb, 45.0 - 41.0, 1e-9);
  ASSERT_EQ(c.adaptiveGainDbEachRun.size(), 2u);
  EXPECT_FALSE(c.adaptiveGainDbEachRun[0].has_value());  // run 1: the quilt (1000 ms) is slower than every point
  ASSERT_TRUE(c.adaptiveGainDbEachRun[1].has_value());   // run 2: 2000 ms between 1000 and 2200 ms in log2 time
  EXPECT_NEAR(*c.adaptiveGainDbEachRun[1], 40.0 + 5.0 * (1.0 / std::log2(2.2)) - 41.0, 1e-9);
}

TEST(EmbreeBvhBuild, EveryTriangleSitsInExactlyOneLeafInsideItsBounds) {
  const Scene scene = loadScene("builtin:sphere");
  const EmbreeBvhBuild build = buildEmbreeBvh(scene.positions, scene.triangles, 4);
  std::vector<int> seen(scene.triangles.size(), 0);
  for (const bvh::Bvh2Node& node : build.tree.nodes) {
    if (!node.isLeaf()) continue;
    EXPECT_LE(node.triCount, 4u);
    for (std::uint32_t k = 0; k < node.triCount; ++k) {
      const std::uint32_t t = build.tree.primIndex[node.leftFirst + k];
      ++seen[t];
      for (int v = 0; v < 3; ++v) {
        const glm::vec3 p = scene.positions[scene.triangles[t][v]];
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, node.lo)) && glm::all(glm::lessThanEqual(p, node.hi)));
      }
    }
  }
  for (std::size_t t = 0; t < seen.size(); ++t) ASSERT_EQ(seen[t], 1) << "triangle " << t;
  EXPECT_NEAR(build.tree.report.sahCost, bvh::sahCost(build.tree), 1e-9);
}

}  // namespace
}  // namespace ht::bench
