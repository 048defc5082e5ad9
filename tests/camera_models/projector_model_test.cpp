// HPO projector array (docs/OPTICS.md §6, §9 M3). Consistency checks written without the model code: the screen point
// is computed here from the config (linear mapping, or the fixture's homography), and each ray must pass through it,
// start on the observer line (z = Dobs, y = h), continue its projector's line P_k -> S horizontally and take its
// vertical slope from the observer. Then float vs double over whole projector images of the 70-projector wall.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "camera_models/projector_model.h"
#include "camera_models/projector_setup.h"
#include "camera_test_support.h"

namespace ht {
namespace {

#ifdef HT_SANITIZED_BUILD
constexpr std::uint32_t kProjectorStride = 41;
#else
constexpr std::uint32_t kProjectorStride = 3;
#endif

DisplayConfig smallArray() { return test::loadFixture("display_projector_small.json"); }

// Screen point of projector pixel position (px, py), display units: Doronin's linear map (docs/OPTICS.md §6), or the
// fixture's explicit homography (row-major, on (px, py, 1)).
glm::dvec3 expectedScreenPoint(const ProjectorArrayConfig& a, std::uint32_t k, glm::dvec2 pixel) {
  const ProjectorConfig& projector = a.projectors[k];
  if (!projector.homography)
    return {-0.5 * a.screenWidth + a.screenWidth * pixel.x / projector.width,
            -0.5 * a.screenHeight + a.screenHeight * pixel.y / projector.height, 0.0};
  const auto& h = *projector.homography;
  const double w = h[6] * pixel.x + h[7] * pixel.y + h[8];
  return {(h[0] * pixel.x + h[1] * pixel.y + h[2]) / w, (h[3] * pixel.x + h[4] * pixel.y + h[5]) / w, 0.0};
}

TEST(ProjectorModel, RayThroughScreenPointFromObserverLine) {
  const DisplayConfig config = smallArray();
  const ProjectorArrayConfig& a = *config.projectorArray;
  const gpu_shared::ProjectorArrayParams p = makeProjectorArrayParams(config, test::testBounds());
  // Fixture placement: target (0.5, 1, -2), screen height 600 units -> 1.5 world units.
  const glm::dvec3 target(0.5, 1.0, -2.0);
  const double scale = 1.5 / 600.0;
  for (std::uint32_t k = 0; k < a.projectors.size(); ++k) {
    const ProjectorConfig& projector = a.projectors[k];
    for (std::uint32_t x : {0u, projector.width / 3, projector.width - 1}) {
      for (std::uint32_t y : {0u, projector.height / 2, projector.height - 1}) {
        for (glm::vec2 xi : {glm::vec2(0.5f), glm::vec2(0.0f), glm::vec2(0.99f, 0.25f)}) {
          glm::vec3 origin, dir;
          gpu_shared::projector_ray(p, x, y, k, xi, origin, dir);
          const glm::dvec3 o = (glm::dvec3(origin) - target) / scale;  // back to display units
          const glm::dvec3 d(dir);
          ASSERT_NEAR(glm::length(d), 1.0, 1e-6);
          // On the observer line.
          EXPECT_NEAR(o.z, a.observerDistance, 1e-3);
          EXPECT_NEAR(o.y, a.observerHeight, 1e-3);
          // Meets the screen z = 0 at the projector's screen point.
          const glm::dvec3 s = expectedScreenPoint(a, k, {x + xi.x, y + xi.y});
          const glm::dvec3 hit = o + (-o.z / d.z) * d;
          EXPECT_NEAR(hit.x, s.x, 2e-3) << k << " " << x << " " << y;
          EXPECT_NEAR(hit.y, s.y, 2e-3) << k << " " << x << " " << y;
          // Horizontal direction from the projector: P_k, S and the origin are collinear in the x-z plane.
          const glm::dvec2 fromProjector(s.x - projector.position.x, s.z - projector.position.z);
          const glm::dvec2 horizontal(d.x, d.z);
          const double sine = (fromProjector.x * horizontal.y - fromProjector.y * horizontal.x) /
                              (glm::length(fromProjector) * glm::length(horizontal));
          EXPECT_NEAR(sine, 0.0, 2e-6);
          // Vertical perspective from the observer: slope dy/dz is (S.y - h)/(0 - Dobs), whatever the projector's y.
          EXPECT_NEAR(d.y / d.z, (s.y - a.observerHeight) / -a.observerDistance, 2e-6);
        }
      }
    }
  }
}

// A tracked viewer: moving the observer up tilts every ray's vertical slope but not its horizontal direction.
TEST(ProjectorModel, ObserverHeightOnlyChangesVerticalPerspective) {
  DisplayConfig low = smallArray(), high = smallArray();
  low.projectorArray->observerHeight = 0.0;
  high.projectorArray->observerHeight = 400.0;
  const gpu_shared::ProjectorArrayParams pl = makeProjectorArrayParams(low, test::testBounds());
  const gpu_shared::ProjectorArrayParams ph = makeProjectorArrayParams(high, test::testBounds());
  glm::vec3 ol, dl, oh, dh;
  gpu_shared::projector_ray(pl, 100, 30, 0, glm::vec2(0.5f), ol, dl);
  gpu_shared::projector_ray(ph, 100, 30, 0, glm::vec2(0.5f), oh, dh);
  EXPECT_NEAR(ol.x, oh.x, 1e-6);
  EXPECT_NEAR(dl.x / dl.z, dh.x / dh.z, 1e-6);
  EXPECT_NEAR(oh.y - ol.y, 400.0 * 1.5 / 600.0, 1e-5);
  EXPECT_LT(dh.y, dl.y);  // looking down from higher up
}

// Scattering rotates the ray about the vertical through S by dA = sigma * sqrt(-2 ln(1 - u)) cos(2 pi v),
// sigma = as / 1.11741 / sqrt(2) (docs/OPTICS.md §9 M3).
TEST(ProjectorModel, ScatteringRotatesAboutScreenPoint) {
  const DisplayConfig config = smallArray();
  const gpu_shared::ProjectorArrayParams p = makeProjectorArrayParams(config, test::testBounds());
  glm::vec3 o0, d0, o1, d1;
  gpu_shared::projector_ray(p, 200, 100, 2, glm::vec2(0.5f), o0, d0);
  gpu_shared::projector_scattered_ray(p, 200, 100, 2, glm::vec2(0.5f), glm::vec2(0.6f, 0.25f), o1, d1);
  EXPECT_LT(test::angleBetween(glm::dvec3(d0), glm::dvec3(d1)), 1e-6);  // cos(pi/2) = 0: no rotation
  const double u = 0.8, v = 0.1;
  const double sigma = 0.02 / 1.11741 / std::sqrt(2.0);
  const double expected = sigma * std::sqrt(-2.0 * std::log(1.0 - u)) * std::cos(2.0 * std::numbers::pi * v);
  gpu_shared::projector_scattered_ray(p, 200, 100, 2, glm::vec2(0.5f), glm::vec2(float(u), float(v)), o1, d1);
  const double yaw0 = std::atan2(d0.x, -d0.z), yaw1 = std::atan2(d1.x, -d1.z);
  EXPECT_NEAR(yaw0 - yaw1, expected, 2e-6);  // rotation about +y by dA lowers the yaw atan(x / -z) by dA
  EXPECT_NEAR(d1.y, d0.y, 1e-6);
  // Both rays meet the plane of the screen at the same point.
  const double z = -2.0;
  const glm::dvec3 h0 = glm::dvec3(o0) + (z - o0.z) / d0.z * glm::dvec3(d0);
  const glm::dvec3 h1 = glm::dvec3(o1) + (z - o1.z) / d1.z * glm::dvec3(d1);
  EXPECT_LT(glm::length(h0 - h1), 1e-5);
}

TEST(ProjectorModel, AutoScatteringIsOneAndAHalfCentralSpacings) {
  const DisplayConfig wall = builtinDisplay("holovizio-wall-70");
  // Projectors 34 and 35 at x = -16 and +16 mm, 1800 mm behind the screen.
  const double expected = 1.5 * 2.0 * std::atan(16.0 / 1800.0);
  EXPECT_NEAR(resolveAngularScattering(*wall.projectorArray), expected, 1e-12);
  EXPECT_NEAR(makeProjectorArrayParams(wall, test::testBounds()).observer.z, expected, 1e-7);
}

// Float vs double over whole projector images of the 70-projector wall and of the calibrated fixture, corners
// included (every kProjectorStride-th pixel plus all four corner pixels at xi = 0 and xi -> 1).
void measureFloatAgainstReference(const DisplayConfig& config, double& maxAngle, double& maxOrigin,
                                  double& sceneScale) {
  const Bounds3 bounds = test::testBounds();
  const gpu_shared::ProjectorArrayParams p = makeProjectorArrayParams(config, bounds);
  const ProjectorArrayReference reference(config, bounds);
  sceneScale = glm::length(glm::dvec3(bounds.hi) - glm::dvec3(bounds.lo));
  auto check = [&](std::uint32_t x, std::uint32_t y, std::uint32_t k, glm::vec2 xi) {
    glm::vec3 o, d;
    gpu_shared::projector_ray(p, x, y, k, xi, o, d);
    const ReferenceRay r = reference.ray(x, y, k, glm::dvec2(xi));
    maxAngle = std::max(maxAngle, test::angleBetween(glm::dvec3(d), r.dir));
    maxOrigin = std::max(maxOrigin, glm::length(glm::dvec3(o) - r.origin));
  };
  const ProjectorArrayConfig& a = *config.projectorArray;
  for (std::uint32_t k = 0; k < a.projectors.size(); k += (a.projectors.size() > 8 ? 3 : 1)) {
    const std::uint32_t w = a.projectors[k].width, h = a.projectors[k].height;
    for (std::uint32_t y = 0; y < h; y += kProjectorStride)
      for (std::uint32_t x = 0; x < w; x += kProjectorStride) check(x, y, k, glm::vec2(0.5f));
    for (std::uint32_t x : {0u, w - 1})
      for (std::uint32_t y : {0u, h - 1})
        for (glm::vec2 xi : {glm::vec2(0.0f), glm::vec2(0.9999999f)}) check(x, y, k, xi);
  }
}

TEST(ProjectorModel, FloatMatchesDoubleReference) {
  for (const DisplayConfig& config : {builtinDisplay("holovizio-wall-70"), smallArray()}) {
    double maxAngle = 0.0, maxOrigin = 0.0, sceneScale = 0.0;
    measureFloatAgainstReference(config, maxAngle, maxOrigin, sceneScale);
    std::printf("projector %s float vs double: max angle %.3g rad, max origin %.3g (scene scale %.3g)\n",
                config.name.c_str(), maxAngle, maxOrigin, sceneScale);
    EXPECT_LE(maxAngle, 2e-6) << config.name;
    EXPECT_LE(maxOrigin, 1e-6 * sceneScale) << config.name;
  }
}

}  // namespace
}  // namespace ht
