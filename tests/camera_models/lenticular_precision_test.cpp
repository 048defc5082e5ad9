// Shared float model (lenticular_model.h) against the double reference (lenticular_reference.h): phase, direction
// and origin errors over whole panels, and on an 8K (7680x4320) panel where phi reaches ~1200 and one float ulp
// of phi is 1.2e-4.
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "camera_models/lenticular_model.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/lenticular_reference.h"
#include "camera_test_support.h"

namespace ht {
namespace {

struct Sample {
  std::uint32_t x, y, c;
  glm::vec2 xi;
};

struct ErrorStats {
  double phase = 0.0;        // max |t_float - t_double| on the phase circle
  double angle = 0.0;        // max angle between float and double directions (rad)
  double origin = 0.0;       // max |o_float - o_double| (world units)
  double unitLength = 0.0;   // max ||d_float| - 1|
  long skippedNearWrap = 0;  // t within 1e-5 of 0 / 1: the view wraps there, both sides are right
  long samples = 0;
};

// Visits every sample of a panel region; `Visit` is called as visit(Sample).
template <class SampleSource>
ErrorStats measureErrors(const DisplayConfig& config, const Bounds3& bounds, const SampleSource& forEachSample) {
  const gpu_shared::LenticularParams p = makeLenticularParams(config, bounds);
  const LenticularReference reference(config, bounds);
  ErrorStats stats;
  forEachSample([&](const Sample& s) {
    const glm::dvec2 xi(s.xi);
    const double tRef = reference.viewPhase(s.x, s.y, s.c, xi);
    const double t = gpu_shared::lenticular_view_phase(p, s.x, s.y, s.c, s.xi);
    stats.phase = std::max(stats.phase, std::fabs(test::phaseDifference(t, tRef)));
    ++stats.samples;
    if (tRef < 1e-5 || tRef > 1.0 - 1e-5) {
      ++stats.skippedNearWrap;
      return;
    }
    glm::vec3 origin, dir;
    gpu_shared::lenticular_ray(p, s.x, s.y, s.c, s.xi, origin, dir);
    const ReferenceRay ray = reference.rayForPhase(tRef, reference.sampleUV(s.x, s.y, s.c, xi));
    stats.angle = std::max(stats.angle, test::angleBetween(glm::dvec3(dir), ray.dir));
    stats.origin = std::max(stats.origin, glm::length(glm::dvec3(origin) - ray.origin));
    stats.unitLength = std::max(stats.unitLength, std::fabs(glm::length(glm::dvec3(dir)) - 1.0));
  });
  return stats;
}

void report(const char* what, const ErrorStats& s, double scale) {
  std::printf(
      "[ %s ] %ld samples: max |dt| %.3g, angle %.3g rad, origin %.3g (%.3g of |target| + D), "
      "||d|-1| %.3g, %ld near the wrap\n",
      what, s.samples, s.phase, s.angle, s.origin, s.origin / scale, s.unitLength, s.skippedNearWrap);
}

// Every `stride`-th pixel of the panel, all three channels, xi from a fixed low-discrepancy sequence (R2).
struct WholePanel {
  std::uint32_t width, height, stride;
  template <class Visit>
  void operator()(const Visit& visit) const {
    std::uint32_t n = 0;
    for (std::uint32_t y = 0; y < height; y += stride)
      for (std::uint32_t x = 0; x < width; x += stride)
        for (std::uint32_t c = 0; c < 3; ++c, ++n) {
          const double a = std::fmod(0.5 + n * 0.7548776662466927, 1.0);
          const double b = std::fmod(0.5 + n * 0.5698402909980532, 1.0);
          visit(Sample{x, y, c, glm::vec2(float(a), float(b))});
        }
  }
};

struct SampleList {
  std::vector<Sample> samples;
  template <class Visit>
  void operator()(const Visit& visit) const {
    for (const Sample& s : samples) visit(s);
  }
};

// The four corners (every channel, footprint corners and centre), the last row and column, and a coarse grid.
SampleList cornersEdgesAndGrid(std::uint32_t width, std::uint32_t height) {
  std::vector<Sample> samples;
  const std::vector<glm::vec2> xis = {{0.0f, 0.0f},    {0.5f, 0.5f},    {0.9999f, 0.9999f},
                                      {0.0f, 0.9999f}, {0.9999f, 0.0f}, {0.31f, 0.77f}};
  for (std::uint32_t y : {0u, height - 1})
    for (std::uint32_t x : {0u, width - 1})
      for (std::uint32_t c = 0; c < 3; ++c)
        for (glm::vec2 xi : xis) samples.push_back({x, y, c, xi});
  for (std::uint32_t x = 0; x < width; ++x) samples.push_back({x, height - 1, x % 3, glm::vec2(0.5f)});
  for (std::uint32_t y = 0; y < height; ++y) samples.push_back({width - 1, y, y % 3, glm::vec2(0.5f)});
  WholePanel{width, height, 13}([&](const Sample& s) { samples.push_back(s); });
  return {std::move(samples)};
}

// Bounds, derived in lenticular_model.h / lenticular_vendor_test.cpp: phase error ~2e-7 (split integer part, a few
// roundings of 2^-24..2^-23 on terms below 4), bound 1e-6. Direction: theta = viewCone*(t - 0.5) moves by
// <= 0.9 rad * 1e-6, plus float roundings in tan/normalize of ~1e-7: 2e-6 rad. Origin: o.x = D tan(theta) moves by
// D*sec^2(theta)*dtheta (~1.2 D dtheta for |theta| <= 25 deg), and the float origin target + o is rounded to half an
// ulp of its magnitude (<= |target| + D): bound 1e-6 of that scale, |target| + D.
constexpr double kPhaseBound = 1e-6;
constexpr double kAngleBound = 2e-6;
constexpr double kOriginBoundOfScale = 1e-6;

template <class SampleSource>
void expectWithinBounds(const char* what, const DisplayConfig& config, const SampleSource& samples) {
  const Bounds3 bounds = test::testBounds();
  const ErrorStats stats = measureErrors(config, bounds, samples);
  const LenticularCamera camera = resolveLenticularCamera(config, bounds);
  const double originScale = glm::length(camera.target) + camera.focalDistance;
  report(what, stats, originScale);
  EXPECT_LT(stats.phase, kPhaseBound);
  EXPECT_LT(stats.angle, kAngleBound);
  EXPECT_LT(stats.origin, kOriginBoundOfScale * originScale);
  EXPECT_LT(stats.unitLength, 1e-6);
  EXPECT_LT(stats.skippedNearWrap, stats.samples / 1000 + 20);
}

TEST(CameraModelsPrecision, PortraitWholePanel) {
  expectWithinBounds("portrait", builtinDisplay("portrait"), WholePanel{1536, 2048, 1});
}

TEST(CameraModelsPrecision, Gen1WholePanel) {
  expectWithinBounds("gen1-8.9", builtinDisplay("gen1-8.9"), WholePanel{2560, 1600, 2});
}

TEST(CameraModelsPrecision, Gen3LandscapeWholePanel) {
  expectWithinBounds("gen3-16-landscape", builtinDisplay("gen3-16-landscape"), WholePanel{3840, 2160, 3});
}

TEST(CameraModelsPrecision, EightKClassicCornersAndGrid) {
  expectWithinBounds("8k classic", test::eightKDisplay(0), cornersEdgesAndGrid(7680, 4320));
}

TEST(CameraModelsPrecision, EightKGen3CornersAndGrid) {
  expectWithinBounds("8k gen3 cells", test::eightKDisplay(2), cornersEdgesAndGrid(7680, 4320));
}

TEST(CameraModelsPrecision, EightKFlippedBgrForwardOrder) {
  expectWithinBounds("8k flipX bgr invView0", test::eightKDisplay(0, true, true, false),
                     cornersEdgesAndGrid(7680, 4320));
}

// Why the split matters: the vendor's float formula (u + c*subp + v*tilt)*pitch_s - center loses ~1e-4 on 8K, and so
// does the fallback without split constants (parameter blocks built by hand with cellOffset[0..1].zw zero).
TEST(CameraModelsPrecision, UnsplitFloatPhaseIsWorseOnEightK) {
  const DisplayConfig config = test::eightKDisplay(0);
  const Bounds3 bounds = test::testBounds();
  gpu_shared::LenticularParams p = makeLenticularParams(config, bounds);
  gpu_shared::LenticularParams unsplit = p;
  unsplit.cellOffset[0].z = unsplit.cellOffset[0].w = 0.0f;
  unsplit.cellOffset[1].z = unsplit.cellOffset[1].w = 0.0f;
  const LenticularReference reference(config, bounds);
  double splitError = 0.0, unsplitError = 0.0, vendorFloatError = 0.0;
  for (const Sample& s : cornersEdgesAndGrid(7680, 4320).samples) {
    const double tRef = reference.viewPhase(s.x, s.y, s.c, glm::dvec2(s.xi));
    splitError = std::max(
        splitError, std::fabs(test::phaseDifference(gpu_shared::lenticular_view_phase(p, s.x, s.y, s.c, s.xi), tRef)));
    unsplitError = std::max(unsplitError, std::fabs(test::phaseDifference(
                                              gpu_shared::lenticular_view_phase(unsplit, s.x, s.y, s.c, s.xi), tRef)));
    // holoplaycore.js formula in float with float uniforms, at the same sample point.
    const glm::vec2 uv = gpu_shared::lenticular_sample_uv(p, s.x, s.y, s.c, s.xi);
    const float phi = (uv.x + uv.y * p.phase.y) * p.phase.x - p.phase.w;
    vendorFloatError =
        std::max(vendorFloatError, std::fabs(test::phaseDifference(1.0 - (phi - std::floor(phi)), tRef)));
  }
  std::printf("[ 8k ] max |dt|: split %.3g, unsplit fallback %.3g, vendor-style float %.3g\n", splitError, unsplitError,
              vendorFloatError);
  EXPECT_LT(splitError, kPhaseBound);
  EXPECT_GT(vendorFloatError, 1e-5);                       // the naive formula misses the ~1e-5 goal on 8K ...
  EXPECT_GT(unsplitError, 10.0 * splitError);              // ... the fallback too ...
  EXPECT_LT(unsplitError, 1200.0 * std::ldexp(1.0, -21));  // ... but stays within a few ulp of phi ~ 1200
}

}  // namespace
}  // namespace ht
