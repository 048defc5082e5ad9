// Consistency checks written without the model code: at each view-bin centre the direct ray equals the quilt camera
// ray of docs/OPTICS.md §9 M1 (looking-glass-webxr LookingGlassXRDevice.ts) for camera i through the same focal-plane
// point; directions are unit; every ray meets the focal plane inside the focal rectangle; view 0 is leftmost.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "camera_models/lenticular_model.h"
#include "camera_models/lenticular_params.h"
#include "camera_test_support.h"

namespace ht {
namespace {

// docs/OPTICS.md §9 M1, from the config's explicit numbers (no resolveLenticularCamera):
//   D = 0.5*targetDiam/tan(fovy/2); theta_i = viewCone_rad*((i+0.5)/N - 0.5); o_i = (D tan(theta_i), 0, D)
//   P = ((u - 0.5)*aspect*targetDiam, (v - 0.5)*targetDiam, 0); d = normalize(P - o_i); world = target + local.
struct QuiltCamera {
  glm::dvec3 origin, dir;
};
QuiltCamera quiltCameraRay(const DisplayConfig& config, int i, int views, glm::dvec2 uv) {
  const LookingGlassCalibration& c = *config.calibration;
  const double size = *config.camera.size, aspect = double(c.screenW) / double(c.screenH);
  const double d = 0.5 * size / std::tan(0.5 * config.camera.fovyDeg * std::numbers::pi / 180.0);
  const double cone = c.viewCone * config.camera.depthiness * std::numbers::pi / 180.0;
  const double theta = cone * ((i + 0.5) / views - 0.5);
  const glm::dvec3 o(d * std::tan(theta), 0.0, d);
  const glm::dvec3 p((uv.x - 0.5) * aspect * size, (uv.y - 0.5) * size, 0.0);
  return {*config.camera.target + o, glm::normalize(p - o)};
}

// display_portrait_by_path.json: target (0, 0.5, -1), size 1.5, fovy 16, depthiness 1.25 (all explicit).
DisplayConfig explicitPortrait() { return test::loadFixture("display_portrait_by_path.json"); }

TEST(CameraModelsConsistency, BinCentreRayEqualsQuiltCamera) {
  const DisplayConfig config = explicitPortrait();
  const gpu_shared::LenticularParams p = makeLenticularParams(config, test::testBounds());
  const int views = 48;
  double maxAngle = 0.0, maxOrigin = 0.0;
  for (int i = 0; i < views; ++i) {
    for (double u : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      for (double v : {0.0, 0.4, 1.0}) {
        glm::vec3 origin, dir;
        gpu_shared::lenticular_ray_for_phase(p, (float(i) + 0.5f) / float(views), glm::vec2(u, v), origin, dir);
        const QuiltCamera expected = quiltCameraRay(config, i, views, {u, v});
        maxAngle = std::max(maxAngle, test::angleBetween(glm::dvec3(dir), expected.dir));
        maxOrigin = std::max(maxOrigin, glm::length(glm::dvec3(origin) - expected.origin));
      }
    }
  }
  EXPECT_LT(maxAngle, 1e-6);
  EXPECT_LT(maxOrigin, 1e-6 * 5.3);  // D = 5.34 here: float rounding of |origin|
}

// End to end through real subpixels: where the vendor phase (computed here, docs/OPTICS.md §3.1) is within 2e-4 of a
// bin centre, the subpixel's ray is camera i's ray through the subpixel's focal-plane point (u + c*subp, v), up to
// the angle that 2e-4 of phase makes (viewCone_rad * 2e-4).
TEST(CameraModelsConsistency, SubpixelsAtBinCentresSeeQuiltCameras) {
  const DisplayConfig config = explicitPortrait();
  const LookingGlassCalibration& c = *config.calibration;
  const gpu_shared::LenticularParams p = makeLenticularParams(config, test::testBounds());
  const LenticularShaderValues s = lenticularShaderValues(c);
  const int views = 48;
  const double tolerance = 2e-4;
  const double cone = c.viewCone * config.camera.depthiness * std::numbers::pi / 180.0;
  long matched = 0;
  for (std::uint32_t y = 0; y < c.screenH; y += 3) {
    for (std::uint32_t x = 0; x < c.screenW; ++x) {
      for (std::uint32_t ch = 0; ch < 3; ++ch) {
        const double u = (x + 0.5) / c.screenW + ch * s.subp, v = (y + 0.5) / c.screenH;
        const double phi = (u + v * s.tilt) * s.pitch - s.center;
        const double t = 1.0 - (phi - std::floor(phi));
        const double bin = t * views - 0.5;
        const int i = static_cast<int>(std::lround(bin));
        if (std::fabs(bin - i) > tolerance * views || i < 0 || i >= views) continue;
        glm::vec3 origin, dir;
        gpu_shared::lenticular_ray(p, x, y, ch, glm::vec2(0.5f), origin, dir);
        const QuiltCamera expected = quiltCameraRay(config, i, views, {u, v});
        EXPECT_LT(test::angleBetween(glm::dvec3(dir), expected.dir), cone * tolerance * 1.2 + 1e-6);
        ++matched;
      }
    }
  }
  EXPECT_GT(matched, 1000);
}

struct Extent {
  double halfWidth, halfHeight, marginX, marginY;
};

// Rays meet the plane z = target.z at the focal-plane point of their sample, inside the focal rectangle (grown by the
// largest Gen3 cell offset: those subpixels sit up to that far outside their pixel), with unit directions.
void expectRaysThroughFocalRectangle(const DisplayConfig& config, std::uint32_t stride) {
  const Bounds3 bounds = test::testBounds();
  const gpu_shared::LenticularParams p = makeLenticularParams(config, bounds);
  const LookingGlassCalibration& c = *config.calibration;
  const LenticularCamera camera = resolveLenticularCamera(config, bounds);
  double maxOffset = 0.0;
  for (const SubpixelCell& cell : c.subpixelCells)
    for (std::uint32_t ch = 0; ch < 3; ++ch)
      maxOffset = std::max({maxOffset, std::fabs(cell.offset(ch).x), std::fabs(cell.offset(ch).y)});
  const double pixel = camera.size / c.screenH;  // square pixels: aspect*size/W = size/H
  // Classic model: holoplaycore.js samples blue at u + 2*subp, 2/3 px right of the pixel centre, and the footprint
  // adds 1/6 px: the last column's blue footprint reaches 1/3 px past the panel edge (mirrored with flipImageX).
  const double classicOverhang = c.cellPatternMode == 0 ? 1.0 / 3.0 : 0.0;
  const double halfWidth =
      0.5 * camera.aspect * camera.size + (maxOffset + classicOverhang) * pixel + 1e-6 * camera.size;
  const double halfHeight = 0.5 * camera.size + maxOffset * pixel + 1e-6 * camera.size;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 0.9999f);
  for (std::uint32_t y = 0; y < c.screenH; y += stride) {
    for (std::uint32_t x = 0; x < c.screenW; x += stride) {
      for (std::uint32_t ch = 0; ch < 3; ++ch) {
        glm::vec3 origin, dir;
        gpu_shared::lenticular_ray(p, x, y, ch, glm::vec2(unit(rng), unit(rng)), origin, dir);
        ASSERT_NEAR(glm::length(glm::dvec3(dir)), 1.0, 1e-6);
        ASSERT_LT(dir.z, 0.0f);  // toward the display
        const double s = (camera.target.z - origin.z) / dir.z;
        const glm::dvec3 hit = glm::dvec3(origin) + s * glm::dvec3(dir) - camera.target;
        ASSERT_LE(std::fabs(hit.x), halfWidth) << x << "," << y << "," << ch;
        ASSERT_LE(std::fabs(hit.y), halfHeight) << x << "," << y << "," << ch;
      }
    }
  }
  // The corner subpixels reach the rectangle's corners (the rectangle is covered, not just contained).
  glm::vec3 origin, dir;
  gpu_shared::lenticular_ray(p, c.screenW - 1, c.screenH - 1, 2, glm::vec2(0.9999f), origin, dir);
  const double s = (camera.target.z - origin.z) / dir.z;
  const glm::dvec3 hit = glm::dvec3(origin) + s * glm::dvec3(dir) - camera.target;
  EXPECT_GT(std::fabs(hit.x), 0.5 * camera.aspect * camera.size - 2.0 * pixel);
  EXPECT_GT(std::fabs(hit.y), 0.5 * camera.size - 2.0 * pixel);
}

TEST(CameraModelsConsistency, RaysMeetFocalRectanglePortrait) {
  expectRaysThroughFocalRectangle(builtinDisplay("portrait"), 5);
}

TEST(CameraModelsConsistency, RaysMeetFocalRectangleGen3) {
  expectRaysThroughFocalRectangle(builtinDisplay("gen3-16-landscape"), 9);
}

TEST(CameraModelsConsistency, RaysMeetFocalRectangleEightKFlipped) {
  expectRaysThroughFocalRectangle(test::eightKDisplay(2, true, true), 23);
}

// The footprint: xi = (0.5, 0.5) is the vendor sample point (u + c*subp, v); xi spans 1/3 px by 1 px around it.
TEST(CameraModelsConsistency, FootprintAroundVendorSamplePoint) {
  const DisplayConfig config = builtinDisplay("portrait");
  const gpu_shared::LenticularParams p = makeLenticularParams(config, test::testBounds());
  const double subp = 1.0 / (3.0 * 1536.0);
  for (std::uint32_t ch = 0; ch < 3; ++ch) {
    const glm::dvec2 centre = glm::dvec2(gpu_shared::lenticular_sample_uv(p, 100, 200, ch, glm::vec2(0.5f)));
    EXPECT_NEAR(centre.x, 100.5 / 1536.0 + ch * subp, 1e-7);
    EXPECT_NEAR(centre.y, 200.5 / 2048.0, 1e-7);
    const glm::dvec2 lo = glm::dvec2(gpu_shared::lenticular_sample_uv(p, 100, 200, ch, glm::vec2(0.0f)));
    const glm::dvec2 hi = glm::dvec2(gpu_shared::lenticular_sample_uv(p, 100, 200, ch, glm::vec2(1.0f)));
    EXPECT_NEAR(hi.x - lo.x, subp, 1e-7);
    EXPECT_NEAR(hi.y - lo.y, 1.0 / 2048.0, 1e-7);
  }
}

// Gen3 (mode 2 = xPos % 2): pixel (x, y) uses cell x % 2 and puts channel c at (x+0.5+offX, y+0.5+offY).
TEST(CameraModelsConsistency, Gen3SamplePointsUseCellOffsets) {
  const DisplayConfig config = builtinDisplay("gen3-16-landscape");
  const gpu_shared::LenticularParams p = makeLenticularParams(config, test::testBounds());
  const std::vector<SubpixelCell>& cells = config.calibration->subpixelCells;
  for (std::uint32_t x : {10u, 11u}) {
    for (std::uint32_t ch = 0; ch < 3; ++ch) {
      const glm::dvec2 offset = cells[x % 2].offset(ch);
      const glm::dvec2 uv = glm::dvec2(gpu_shared::lenticular_sample_uv(p, x, 20, ch, glm::vec2(0.5f)));
      EXPECT_NEAR(uv.x, (x + 0.5 + offset.x) / 3840.0, 1e-7);
      EXPECT_NEAR(uv.y, (20.5 + offset.y) / 2160.0, 1e-7);
    }
  }
}

// View 0 is the leftmost camera (docs/OPTICS.md §4.1, §4.3): t -> 0 puts the origin left of the target.
TEST(CameraModelsConsistency, ViewZeroIsLeftmost) {
  const DisplayConfig config = explicitPortrait();
  const gpu_shared::LenticularParams p = makeLenticularParams(config, test::testBounds());
  glm::vec3 left, right, centre, dir;
  gpu_shared::lenticular_ray_for_phase(p, 0.0f, glm::vec2(0.5f), left, dir);
  gpu_shared::lenticular_ray_for_phase(p, 0.5f, glm::vec2(0.5f), centre, dir);
  gpu_shared::lenticular_ray_for_phase(p, 0.99f, glm::vec2(0.5f), right, dir);
  EXPECT_LT(left.x, centre.x);
  EXPECT_LT(centre.x, right.x);
  EXPECT_FLOAT_EQ(centre.x, 0.0f);
  // The full cone: the t = 0 camera sits at theta = -viewCone/2.
  const double d = 0.5 * 1.5 / std::tan(8.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(left.x, -d * std::tan(0.5 * 50.0 * std::numbers::pi / 180.0), 1e-5);
}

// flipImageX / flipImageY mirror the focal-plane point.
TEST(CameraModelsConsistency, FlipImageMirrorsFocalPoint) {
  DisplayConfig config = explicitPortrait();
  config.calibration->flipImageX = true;
  config.calibration->flipImageY = true;
  const gpu_shared::LenticularParams p = makeLenticularParams(config, test::testBounds());
  glm::vec3 origin, dir;
  gpu_shared::lenticular_ray_for_phase(p, 0.5f, glm::vec2(0.25f, 0.1f), origin, dir);
  const double s = (-1.0 - origin.z) / dir.z;
  const glm::dvec3 hit = glm::dvec3(origin) + s * glm::dvec3(dir);
  EXPECT_NEAR(hit.x, (0.75 - 0.5) * 0.75 * 1.5, 1e-6);
  EXPECT_NEAR(hit.y, 0.5 + (0.9 - 0.5) * 1.5, 1e-6);
}

}  // namespace
}  // namespace ht
