// Raw -> shader values (docs/OPTICS.md §2 worked examples), camera resolution (docs/OPTICS.md §4.3) and the
// LenticularParams / PinholeParams blocks.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "camera_models/lenticular_params.h"
#include "camera_models/pinhole_model.h"
#include "camera_test_support.h"
#include "common/error.h"

namespace ht {
namespace {

using test::fixturePath;
using test::loadFixture;

// The worked examples of docs/OPTICS.md §2 are quoted to a given number of digits: compare to half a unit of the last
// one.
TEST(CameraModelsShaderValues, PortraitPr56WorkedExample) {
  LenticularShaderValues v = lenticularShaderValues(*loadFixture("portrait_pr56_visual.json").calibration);
  EXPECT_NEAR(v.pitch, 246.973, 0.0005);
  EXPECT_NEAR(v.tilt, -0.18489, 0.000005);
  EXPECT_NEAR(v.subp, 2.1701e-4, 0.00005e-4);
  EXPECT_DOUBLE_EQ(v.center, 0.40277382731437683);
}

TEST(CameraModelsShaderValues, Gen1OriginalWorkedExample) {
  LenticularShaderValues v = lenticularShaderValues(*loadFixture("gen1_8.9_original_visual.json").calibration);
  EXPECT_NEAR(v.pitch, 370.625, 0.0005);
  EXPECT_NEAR(v.tilt, 0.11982, 0.000005);
  // Close to the hand-entered pitch 370.66407267416486 of lonetech/LookingGlass quiltshader.glsl (docs/OPTICS.md §2).
  EXPECT_NEAR(v.pitch, 370.66407267416486, 0.05);
}

TEST(CameraModelsShaderValues, GoTemplateWorkedExample) {
  LenticularShaderValues v = lenticularShaderValues(*loadFixture("go_template_visual.json").calibration);
  EXPECT_NEAR(v.pitch, 233.75, 0.005);
  EXPECT_NEAR(v.tilt, -0.28219, 0.000005);
}

TEST(CameraModelsShaderValues, TaurayFormulaAgrees) {
  // vga-group/tauray src/looking_glass.cc: corrected_pitch = W/dpi*pitch*sin(atan(|slope|)) (docs/OPTICS.md §2).
  for (const char* name : {"portrait_pr56_visual.json", "gen1_8.9_original_visual.json", "go_template_visual.json"}) {
    const LookingGlassCalibration c = *loadFixture(name).calibration;
    const double tauray = c.screenW / c.DPI * c.pitch * std::sin(std::atan(std::fabs(c.slope)));
    EXPECT_NEAR(lenticularShaderValues(c).pitch, tauray, 1e-9 * tauray) << name;
  }
}

TEST(CameraModelsShaderValues, FlipImageXNegatesTiltAndSubp) {
  LookingGlassCalibration c = *loadFixture("portrait_pr56_visual.json").calibration;
  LenticularShaderValues plain = lenticularShaderValues(c);
  c.flipImageX = true;
  LenticularShaderValues flipped = lenticularShaderValues(c);
  EXPECT_EQ(flipped.tilt, -plain.tilt);
  EXPECT_EQ(flipped.subp, -plain.subp);
  EXPECT_EQ(flipped.pitch, plain.pitch);
}

TEST(CameraModelsParams, LenticularParamsFields) {
  DisplayConfig config = loadFixture("display_portrait_by_path.json");  // target (0, 0.5, -1), size 1.5, fovy 16
  gpu_shared::LenticularParams p = makeLenticularParams(config, test::testBounds());
  const double d = 0.5 * 1.5 / std::tan(8.0 * std::numbers::pi / 180.0);
  EXPECT_FLOAT_EQ(p.camera.x, static_cast<float>(d));
  EXPECT_FLOAT_EQ(p.camera.y, 1.5f);
  EXPECT_FLOAT_EQ(p.camera.z, 0.75f);                                                       // 1536 / 2048
  EXPECT_FLOAT_EQ(p.camera.w, static_cast<float>(40.0 * 1.25 * std::numbers::pi / 180.0));  // depthiness 1.25
  EXPECT_FLOAT_EQ(p.panel.x, 1536.0f);
  EXPECT_FLOAT_EQ(p.panel.y, 2048.0f);
  EXPECT_EQ(p.panel.z, 1.0f);  // invView
  EXPECT_EQ(p.panel.w, 0.0f);  // flipSubp
  EXPECT_EQ(p.flags, glm::ivec4(0, 0, 0, 0));
  EXPECT_NEAR(p.phase.x, 246.973, 0.0005);
  EXPECT_EQ(p.localToWorld[3], glm::vec4(0.0f, 0.5f, -1.0f, 1.0f));
  EXPECT_EQ(glm::mat3(p.localToWorld), glm::mat3(1.0f));
  // Split phase rates sum to A = pitch_s/W and B = tilt*pitch_s/H.
  const LenticularShaderValues v = lenticularShaderValues(*config.calibration);
  // (lo is rounded to float: relative error 2^-24 of |lo| <= 2^-12 |rate| for an 11-bit-index panel.)
  const double rateX = v.pitch / 1536.0, rateY = v.tilt * v.pitch / 2048.0;
  EXPECT_NEAR(double(p.cellOffset[0].z) + double(p.cellOffset[0].w), rateX, std::ldexp(std::fabs(rateX), -36));
  EXPECT_NEAR(double(p.cellOffset[1].z) + double(p.cellOffset[1].w), rateY, std::ldexp(std::fabs(rateY), -36));
}

TEST(CameraModelsParams, Gen3CellOffsetsDividedOnce) {
  gpu_shared::LenticularParams p = makeLenticularParams(builtinDisplay("gen3-16-landscape"), test::testBounds());
  EXPECT_EQ(p.flags.x, 2);
  EXPECT_EQ(p.flags.y, 2);
  EXPECT_FLOAT_EQ(p.cellOffset[0].x, static_cast<float>(-0.31 / 3840.0));  // cell 0 R
  EXPECT_FLOAT_EQ(p.cellOffset[0].y, static_cast<float>(0.25 / 2160.0));
  EXPECT_FLOAT_EQ(p.cellOffset[5].y, static_cast<float>(0.25 / 2160.0));  // cell 1 B
  EXPECT_FLOAT_EQ(p.cellOffset[4].x, static_cast<float>(0.28 / 3840.0));  // cell 1 G
  // Building twice gives the same block (no in-place division, cf. looking-glass-webxr PR #59).
  gpu_shared::LenticularParams again = makeLenticularParams(builtinDisplay("gen3-16-landscape"), test::testBounds());
  for (int i = 0; i < 12; ++i) EXPECT_EQ(p.cellOffset[i], again.cellOffset[i]);
}

TEST(CameraModelsParams, AutoTargetAndSizeFitBounds) {
  DisplayConfig config = builtinDisplay("portrait");  // aspect 0.75
  Bounds3 bounds = test::testBounds();                // extent (2.2, 1.6, 1.5), centre (0.3, 1.8, -2.25)
  LenticularCamera camera = resolveLenticularCamera(config, bounds);
  EXPECT_NEAR(camera.target.x, 0.3, 1e-6);
  EXPECT_NEAR(camera.target.y, 1.8, 1e-6);
  EXPECT_NEAR(camera.target.z, -2.25, 1e-6);
  EXPECT_NEAR(camera.size, 1.1 * (2.2 / 0.75), 1e-6);  // x extent limits: 2.2 / 0.75 > 1.6
  EXPECT_NEAR(camera.focalDistance, 0.5 * camera.size / std::tan(7.0 * std::numbers::pi / 180.0), 1e-9);
  EXPECT_NEAR(camera.viewConeRad, 40.0 * std::numbers::pi / 180.0, 1e-12);
  // Tall bounds: the y extent limits.
  Bounds3 tall;
  tall.extend(glm::vec3(0.0f));
  tall.extend(glm::vec3(0.1f, 3.0f, 0.1f));
  EXPECT_NEAR(resolveLenticularCamera(config, tall).size, 3.3, 1e-6);
}

TEST(CameraModelsParams, EmptyBoundsFallBackToWebxrDefaults) {
  LenticularCamera camera = resolveLenticularCamera(builtinDisplay("portrait"), Bounds3{});
  EXPECT_EQ(camera.target, glm::dvec3(0.0));
  EXPECT_EQ(camera.size, 2.0);
}

TEST(CameraModelsParams, PanelLayout) {
  PanelLayout layout = panelLayout(builtinDisplay("gen3-16-landscape"));
  EXPECT_EQ(layout.width, 3840u);
  EXPECT_EQ(layout.height, 2160u);
  EXPECT_FALSE(layout.bgr);
}

TEST(CameraModelsParams, SplitPhaseRateProductsAreExact) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> rate(-2.0, 2.0);
  for (std::uint32_t count : {1u, 1536u, 2160u, 7680u, 32768u}) {
    for (int trial = 0; trial < 50; ++trial) {
      const double r = rate(rng);
      const glm::vec2 split = splitPhaseRate(r, count);
      // hi carries >= 9 significant bits, so |lo| <= 2^-9 |r| and its float rounding is <= 2^-33 |r|.
      EXPECT_NEAR(double(split.x) + double(split.y), r, std::ldexp(std::fabs(r), -33));
      for (std::uint32_t i : {count - 1, count / 2 + 1, count / 3, 1u}) {
        const float product = static_cast<float>(i) * split.x;
        EXPECT_EQ(double(product), double(i) * double(split.x)) << "count " << count << " i " << i;
      }
    }
  }
}

TEST(CameraModelsPinhole, MatchesM0InDouble) {
  DisplayConfig config = loadFixture("display_pinhole.json");  // 640x480, fovy 50, eye (0,1,5) -> lookAt (0,1,0)
  gpu_shared::PinholeParams p = makePinholeParams(config, test::testBounds());
  const double tanHalf = std::tan(25.0 * std::numbers::pi / 180.0), aspect = 640.0 / 480.0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.0f, 0.999f);
  for (std::uint32_t y : {0u, 1u, 240u, 479u}) {
    for (std::uint32_t x : {0u, 320u, 639u}) {
      glm::vec2 xi(unit(rng), unit(rng));
      glm::vec3 o, d;
      gpu_shared::pinhole_ray(p, x, y, xi, o, d);
      // docs/OPTICS.md §9 M0, camera looking down -z from (0,1,5): camera axes equal world axes.
      glm::dvec3 expected = glm::normalize(glm::dvec3((2.0 * (x + xi.x) / 640.0 - 1.0) * aspect * tanHalf,
                                                      (2.0 * (y + xi.y) / 480.0 - 1.0) * tanHalf, -1.0));
      EXPECT_LT(test::angleBetween(glm::dvec3(d), expected), 1e-6);
      EXPECT_EQ(o, glm::vec3(0.0f, 1.0f, 5.0f));
      EXPECT_NEAR(glm::length(glm::dvec3(d)), 1.0, 1e-6);
    }
  }
  // y counts from the bottom: row 0 looks down, the top row looks up.
  glm::vec3 o, low, high;
  gpu_shared::pinhole_ray(p, 320, 0, glm::vec2(0.5f), o, low);
  gpu_shared::pinhole_ray(p, 320, 479, glm::vec2(0.5f), o, high);
  EXPECT_LT(low.y, 0.0f);
  EXPECT_GT(high.y, 0.0f);
}

TEST(CameraModelsPinhole, LenticularPreviewIsTheCentreView) {
  DisplayConfig config = builtinDisplay("portrait");
  Bounds3 bounds = test::testBounds();
  PinholeCamera camera = resolvePinholeCamera(config, bounds);
  LenticularCamera display = resolveLenticularCamera(config, bounds);
  EXPECT_EQ(camera.width, 1536u);
  EXPECT_EQ(camera.height, 2048u);
  EXPECT_EQ(camera.fovyDeg, 14.0);
  EXPECT_EQ(camera.lookAt, display.target);
  EXPECT_NEAR(glm::length(camera.eye - (display.target + glm::dvec3(0, 0, display.focalDistance))), 0.0, 1e-12);
  // The top-right corner ray of the preview passes through the top-right corner of the focal rectangle.
  gpu_shared::PinholeParams p = makePinholeParams(config, bounds);
  glm::vec3 o, d;
  gpu_shared::pinhole_ray(p, 1535, 2047, glm::vec2(1.0f), o, d);
  const glm::dvec3 corner = display.target + glm::dvec3(0.5 * display.aspect * display.size, 0.5 * display.size, 0);
  EXPECT_LT(test::angleBetween(glm::dvec3(d), glm::normalize(corner - glm::dvec3(o))), 1e-6);
}

TEST(CameraModelsPinhole, AutoEyeSeesTheBounds) {
  DisplayConfig config =
      parseDisplayConfig(R"({"model":"pinhole","pinhole":{"width":800,"height":600}})", "auto.json", "");
  Bounds3 bounds = test::testBounds();
  PinholeCamera camera = resolvePinholeCamera(config, bounds);
  EXPECT_NEAR(camera.lookAt.x, 0.3, 1e-6);
  EXPECT_GT(camera.eye.z, bounds.hi.z);
  // Every bounds corner projects inside the image.
  const double tanHalf = std::tan(0.5 * camera.fovyDeg * std::numbers::pi / 180.0), aspect = 800.0 / 600.0;
  for (int i = 0; i < 8; ++i) {
    glm::dvec3 corner((i & 1) ? bounds.hi.x : bounds.lo.x, (i & 2) ? bounds.hi.y : bounds.lo.y,
                      (i & 4) ? bounds.hi.z : bounds.lo.z);
    glm::dvec3 rel = corner - camera.eye;
    EXPECT_LT(std::fabs(rel.y / -rel.z), tanHalf);
    EXPECT_LT(std::fabs(rel.x / -rel.z), tanHalf * aspect);
  }
}

}  // namespace
}  // namespace ht
