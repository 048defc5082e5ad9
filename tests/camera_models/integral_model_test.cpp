// Integral imaging / microlens panels (docs/OPTICS.md §7, §9 M4). Checks written without the model code: in the pinhole
// ("centre") case each ray is the line through its LCD pixel and the nearest lens centre (found here by brute force);
// with g = f a thin lens collimates every aperture sample of a pixel (ray transfer, which fixes the lens-term sign);
// rays start on the front plane; bad sections are ConfigErrors; float vs double over whole panels incl. corners.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "camera_models/display_config.h"
#include "camera_models/integral_model.h"
#include "camera_models/integral_setup.h"
#include "camera_test_support.h"
#include "common/error.h"

namespace ht {
namespace {

#ifdef HT_SANITIZED_BUILD
constexpr std::uint32_t kLensStride = 61;
#else
constexpr std::uint32_t kLensStride = 5;
#endif

using nlohmann::json;
constexpr std::uint32_t kWhole = gpu_shared::HT_INTEGRAL_WHOLE_PIXEL;

DisplayConfig smallPanel() { return test::loadFixture("display_integral_small.json"); }

DisplayConfig withSampling(DisplayConfig config, LensSampling sampling) {
  config.integral->sampling = sampling;
  return config;
}

// Nearest lens centre by brute force over the lens indices around q (rotation a, counter-clockwise).
glm::dvec2 nearestLensCentre(const IntegralConfig& c, glm::dvec2 q) {
  const double a = c.lensRotationDeg * std::numbers::pi / 180.0;
  const glm::dvec2 u(std::cos(a), std::sin(a)), v(-std::sin(a), std::cos(a));
  const glm::dvec2 d = q - c.lensOffset;
  const long i0 = std::lround(glm::dot(d, u) / c.lensPitch), j0 = std::lround(glm::dot(d, v) / c.lensPitch);
  glm::dvec2 best(0.0);
  double bestDistance = 1e300;
  for (long i = i0 - 2; i <= i0 + 2; ++i) {
    for (long j = j0 - 2; j <= j0 + 2; ++j) {
      const glm::dvec2 centre = c.lensOffset + c.lensPitch * (double(i) * u + double(j) * v);
      const double distance = glm::length(centre - q);
      if (distance < bestDistance) bestDistance = distance, best = centre;
    }
  }
  return best;
}

TEST(IntegralModel, PinholeRayThroughPixelAndLensCentre) {
  const DisplayConfig config = withSampling(smallPanel(), LensSampling::Centre);
  const IntegralConfig& c = *config.integral;
  const gpu_shared::IntegralParams p = makeIntegralParams(config, test::testBounds());
  const glm::dvec3 target(0.5, 1.0, -2.0);
  const double scale = 1.5 / (480 * 0.1);
  long checked = 0;
  for (std::uint32_t y = 0; y < c.panelHeight; y += 7) {
    for (std::uint32_t x = 0; x < c.panelWidth; x += 7) {
      const glm::dvec2 pixel((x + 0.5 - 320.0) * 0.1, (y + 0.5 - 240.0) * 0.1);
      const glm::dvec2 lens = nearestLensCentre(c, pixel);
      glm::vec3 origin, dir;
      gpu_shared::integral_ray(p, x, y, kWhole, glm::vec2(0.5f), origin, dir);
      const glm::dvec3 o = (glm::dvec3(origin) - target) / scale, d(dir);
      ASSERT_NEAR(glm::length(d), 1.0, 1e-6);
      ASSERT_LT(d.z, 0.0);                   // into the display
      EXPECT_NEAR(o.z, c.frontPlane, 1e-3);  // starts on the front plane
      const glm::dvec3 atLens = o + (-o.z / d.z) * d, atLcd = o + ((-c.gap - o.z) / d.z) * d;
      EXPECT_NEAR(atLens.x, lens.x, 1e-4) << x << "," << y;
      EXPECT_NEAR(atLens.y, lens.y, 1e-4) << x << "," << y;
      EXPECT_NEAR(atLcd.x, pixel.x, 1e-4) << x << "," << y;
      EXPECT_NEAR(atLcd.y, pixel.y, 1e-4) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 5000);
}

// Thin lens at g = f: a point on the focal plane leaves as a parallel bundle (ray-transfer matrix [1 0; -1/f 1] after
// free flight g), whichever aperture point s the ray crosses; with g != f the bundle is not parallel.
TEST(IntegralModel, ApertureSamplesCollimatedAtFocus) {
  DisplayConfig config = withSampling(smallPanel(), LensSampling::Aperture);
  config.integral->focalLength = config.integral->gap;
  const gpu_shared::IntegralParams focused = makeIntegralParams(config, test::testBounds());
  config.integral->focalLength = 2.0 * config.integral->gap;
  const gpu_shared::IntegralParams defocused = makeIntegralParams(config, test::testBounds());
  for (auto [x, y] : {std::pair{10u, 20u}, {333u, 222u}, {639u, 479u}}) {
    glm::vec3 o0, d0, o1, d1, o2, d2;
    gpu_shared::integral_ray(focused, x, y, kWhole, glm::vec2(0.1f, 0.2f), o0, d0);
    gpu_shared::integral_ray(focused, x, y, kWhole, glm::vec2(0.9f, 0.7f), o1, d1);
    EXPECT_LT(test::angleBetween(glm::dvec3(d0), glm::dvec3(d1)), 1e-6);
    EXPECT_GT(glm::length(glm::dvec3(o0) - glm::dvec3(o1)), 1e-3);  // different aperture points
    gpu_shared::integral_ray(defocused, x, y, kWhole, glm::vec2(0.9f, 0.7f), o2, d2);
    gpu_shared::integral_ray(defocused, x, y, kWhole, glm::vec2(0.1f, 0.2f), o1, d1);
    EXPECT_GT(test::angleBetween(glm::dvec3(d2), glm::dvec3(d1)), 1e-3);
  }
}

void measureIntegral(const DisplayConfig& config, double& maxAngle, double& maxOrigin, double& sceneScale) {
  const Bounds3 bounds = test::testBounds();
  const gpu_shared::IntegralParams p = makeIntegralParams(config, bounds);
  const IntegralReference reference(config, bounds);
  const IntegralConfig& c = *config.integral;
  sceneScale = glm::length(glm::dvec3(bounds.hi) - glm::dvec3(bounds.lo));
  auto check = [&](std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::vec2 xi) {
    glm::vec3 o, d;
    gpu_shared::integral_ray(p, x, y, view, xi, o, d);
    const ReferenceRay r = reference.ray(x, y, view, glm::dvec2(xi));
    maxAngle = std::max(maxAngle, test::angleBetween(glm::dvec3(d), r.dir));
    maxOrigin = std::max(maxOrigin, glm::length(glm::dvec3(o) - r.origin));
  };
  for (std::uint32_t y = 0; y < c.panelHeight; y += kLensStride)
    for (std::uint32_t x = 0; x < c.panelWidth; x += kLensStride) {
      const glm::vec2 xi(float((x * 7u) % 10u) / 10.0f + 0.05f, float((y * 3u) % 10u) / 10.0f + 0.05f);
      check(x, y, (x + y) % 4 == 3 ? kWhole : (x + y) % 4, xi);
    }
  for (std::uint32_t x : {0u, c.panelWidth - 1})
    for (std::uint32_t y : {0u, c.panelHeight - 1})
      for (std::uint32_t view : {0u, 2u, kWhole})
        for (glm::vec2 xi : {glm::vec2(0.5f), glm::vec2(0.25f, 0.75f)}) check(x, y, view, xi);
}

TEST(IntegralModel, FloatMatchesDoubleReference) {
  DisplayConfig eightK = builtinDisplay("integral-15-4k");  // scaled to an 8K LCD, 0.045 mm pixels
  eightK.integral->panelWidth = 7680;
  eightK.integral->panelHeight = 4320;
  eightK.integral->pixelPitch = 0.045;
  DisplayConfig rotated = builtinDisplay("integral-15-4k");
  rotated.integral->lensRotationDeg = 9.46;
  rotated.integral->lensOffset = {0.31, -0.17};
  for (const DisplayConfig& config : {builtinDisplay("integral-15-4k"), eightK, rotated, smallPanel(),
                                      withSampling(smallPanel(), LensSampling::Centre)}) {
    double maxAngle = 0.0, maxOrigin = 0.0, sceneScale = 0.0;
    measureIntegral(config, maxAngle, maxOrigin, sceneScale);
    std::printf("integral %s %ux%u rot %g %s float vs double: max angle %.3g rad, max origin %.3g (scene scale %.3g)\n",
                config.name.c_str(), config.integral->panelWidth, config.integral->panelHeight,
                config.integral->lensRotationDeg,
                config.integral->sampling == LensSampling::Aperture ? "aperture" : "centre", maxAngle, maxOrigin,
                sceneScale);
    EXPECT_LE(maxAngle, 2e-6) << config.name;
    EXPECT_LE(maxOrigin, 1e-6 * sceneScale) << config.name;
  }
}

// Stripe subpixels: view c at xi puts the LCD point at x + (c + xi.x)/3 (centre mode: the ray still meets the lens
// centre nearest to that point).
TEST(IntegralModel, StripeSubpixelsSampleTheirThird) {
  const DisplayConfig config = withSampling(smallPanel(), LensSampling::Centre);
  const gpu_shared::IntegralParams p = makeIntegralParams(config, test::testBounds());
  const glm::dvec3 target(0.5, 1.0, -2.0);
  const double scale = 1.5 / 48.0, gap = config.integral->gap;
  for (std::uint32_t c = 0; c < 3; ++c) {
    glm::vec3 origin, dir;
    gpu_shared::integral_ray(p, 100, 50, c, glm::vec2(0.5f), origin, dir);
    const glm::dvec3 o = (glm::dvec3(origin) - target) / scale, d(dir);
    const glm::dvec3 atLcd = o + ((-gap - o.z) / d.z) * d;
    EXPECT_NEAR(atLcd.x, (100.0 + (c + 0.5) / 3.0 - 320.0) * 0.1, 1e-4);
    EXPECT_NEAR(atLcd.y, (50.5 - 240.0) * 0.1, 1e-4);
  }
}

json validSection() {
  return json::parse(R"({"panelWidth": 640, "panelHeight": 480, "pixelPitch": 0.1, "lensPitch": 1.0, "gap": 2,
                         "focalLength": 2, "viewerDistance": 500})");
}

ConfigError integralSectionError(const std::function<void(json&)>& edit) {
  json config = {{"model", "integral"}, {"integral", validSection()}};
  edit(config["integral"]);
  try {
    parseDisplayConfig(config.dump(), "ii.json", "");
  } catch (const ConfigError& e) { return e; }
  ADD_FAILURE() << "expected a ConfigError for " << config.dump();
  return ConfigError("", "", "", "");
}

TEST(IntegralConfig, ParsesAndDefaults) {
  const json config = {{"model", "integral"}, {"integral", validSection()}};
  const DisplayConfig parsed = parseDisplayConfig(config.dump(), "ii.json", "");
  EXPECT_EQ(parsed.model, DisplayModel::Integral);
  EXPECT_EQ(displayModelName(parsed.model), "integral");
  EXPECT_EQ(parsed.integral->frontPlane, 500.0);  // default: the viewer plane
  EXPECT_EQ(parsed.integral->sampling, LensSampling::Centre);
  EXPECT_EQ(parsed.integral->lensOffset, glm::dvec2(0.0));
}

TEST(IntegralConfig, BadValuesRejected) {
  EXPECT_EQ(integralSectionError([](json& s) { s["gap"] = 0; }).field(), "integral.gap");
  EXPECT_EQ(integralSectionError([](json& s) { s["gap"] = -1; }).field(), "integral.gap");
  EXPECT_EQ(integralSectionError([](json& s) { s["lensPitch"] = 0; }).field(), "integral.lensPitch");
  EXPECT_EQ(integralSectionError([](json& s) { s["lensPitch"] = -0.5; }).field(), "integral.lensPitch");
  EXPECT_EQ(integralSectionError([](json& s) { s["focalLength"] = 0; }).field(), "integral.focalLength");
  EXPECT_EQ(integralSectionError([](json& s) { s["pixelPitch"] = "NaN"; }).field(), "integral.pixelPitch");
  EXPECT_EQ(integralSectionError([](json& s) { s["viewerDistance"] = std::nan(""); }).field(),
            "integral.viewerDistance");
  EXPECT_EQ(integralSectionError([](json& s) { s["frontPlane"] = 0; }).field(), "integral.frontPlane");
  EXPECT_EQ(integralSectionError([](json& s) { s["frontPlane"] = 501; }).field(), "integral.frontPlane");
  EXPECT_EQ(integralSectionError([](json& s) { s["panelWidth"] = 0; }).field(), "integral.panelWidth");
  EXPECT_EQ(integralSectionError([](json& s) { s["lensOffset"] = {0, "x"}; }).field(), "integral.lensOffset");
  EXPECT_EQ(integralSectionError([](json& s) { s["sampling"] = "average"; }).field(), "integral.sampling");
  EXPECT_EQ(integralSectionError([](json& s) { s["lensPitchh"] = 1; }).field(), "integral.lensPitchh");
  EXPECT_EQ(integralSectionError([](json& s) { s.erase("gap"); }).field(), "integral.gap");
  EXPECT_THROW(makeIntegralParams(builtinDisplay("portrait"), test::testBounds()), ConfigError);
}

}  // namespace
}  // namespace ht
