// The quilt cameras (docs/OPTICS.md §9 M1): the shared float quilt_ray against the lenticular model at each view's bin
// centre (the direct path reproduces the quilt path there, §9 M2) and against the independent double reference over
// whole tiles, including the corners of an 8K panel's default quilt.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "camera_models/lenticular_model.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/lenticular_reference.h"
#include "camera_models/quilt_model.h"
#include "camera_models/quilt_setup.h"
#include "camera_test_support.h"

namespace ht {
namespace {

#ifdef HT_SANITIZED_BUILD
constexpr std::uint32_t kQuiltStride = 37;
#else
constexpr std::uint32_t kQuiltStride = 1;
#endif

// Quilt view i, tile pixel (x, y) at xi = 0.5, equals the lenticular ray at phase t = (i + 0.5)/N through the same
// focal-plane point uv = ((x + 0.5)/w, (y + 0.5)/h).
void expectQuiltEqualsLenticularAtBinCentres(const DisplayConfig& config) {
  const Bounds3 bounds = test::testBounds();
  const QuiltLayout layout = defaultQuiltLayout(config);
  const gpu_shared::QuiltParams quilt = makeQuiltParams(config, bounds, layout);
  const gpu_shared::LenticularParams lenticular = makeLenticularParams(config, bounds);
  const LenticularReference lenticularReference(config, bounds);
  const QuiltReference quiltReference(config, bounds, layout);
  double maxAngle = 0.0, maxOrigin = 0.0, maxReferenceAngle = 0.0;
  const std::uint32_t xs[] = {0, 1, layout.tileWidth / 3, layout.tileWidth - 1};
  const std::uint32_t ys[] = {0, layout.tileHeight / 2, layout.tileHeight - 1};
  for (std::uint32_t view = 0; view < layout.views(); ++view) {
    const float t = (float(view) + 0.5f) / float(layout.views());
    for (std::uint32_t x : xs) {
      for (std::uint32_t y : ys) {
        const glm::vec2 uv((float(x) + 0.5f) / float(layout.tileWidth), (float(y) + 0.5f) / float(layout.tileHeight));
        glm::vec3 qo, qd, lo, ld;
        gpu_shared::quilt_ray(quilt, x, y, view, glm::vec2(0.5f), qo, qd);
        gpu_shared::lenticular_ray_for_phase(lenticular, t, uv, lo, ld);
        maxAngle = std::max(maxAngle, test::angleBetween(glm::dvec3(qd), glm::dvec3(ld)));
        maxOrigin = std::max(maxOrigin, glm::length(glm::dvec3(qo) - glm::dvec3(lo)));
        // The two double references agree too (both transcribe looking-glass-webxr's camera).
        const ReferenceRay q = quiltReference.ray(x, y, view, {0.5, 0.5});
        const ReferenceRay l = lenticularReference.rayForPhase(
            (view + 0.5) / layout.views(), {(x + 0.5) / layout.tileWidth, (y + 0.5) / layout.tileHeight});
        maxReferenceAngle = std::max(maxReferenceAngle, test::angleBetween(q.dir, l.dir));
        EXPECT_LT(glm::length(q.origin - l.origin), 1e-12 * glm::length(l.origin) + 1e-12);
      }
    }
  }
  const LenticularCamera camera = resolveLenticularCamera(config, bounds);
  EXPECT_LT(maxAngle, 1e-6);
  EXPECT_LT(maxOrigin, 1e-6 * (camera.focalDistance + glm::length(camera.target)));
  EXPECT_LT(maxReferenceAngle, 1e-13);
}

TEST(QuiltModel, BinCentresEqualLenticularPortrait) {
  expectQuiltEqualsLenticularAtBinCentres(builtinDisplay("portrait"));
}
TEST(QuiltModel, BinCentresEqualLenticularGo) { expectQuiltEqualsLenticularAtBinCentres(builtinDisplay("go")); }
TEST(QuiltModel, BinCentresEqualLenticularEightK) { expectQuiltEqualsLenticularAtBinCentres(test::eightKDisplay(2)); }

// Float vs double over whole tiles of the first, middle and last view of the 8K panel's quilt (7x7, 1170 x 1170 px
// tiles), corners included, at the pixel corners and centre.
TEST(QuiltModel, FloatMatchesDoubleReferenceEightK) {
  const DisplayConfig config = test::eightKDisplay(2);
  const Bounds3 bounds = test::testBounds();
  const QuiltLayout layout = defaultQuiltLayout(config);
  const gpu_shared::QuiltParams p = makeQuiltParams(config, bounds, layout);
  const QuiltReference reference(config, bounds, layout);
  const double sceneScale = glm::length(glm::dvec3(bounds.hi) - glm::dvec3(bounds.lo));
  double maxAngle = 0.0, maxOrigin = 0.0;
  auto check = [&](std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::vec2 xi) {
    glm::vec3 o, d;
    gpu_shared::quilt_ray(p, x, y, view, xi, o, d);
    const ReferenceRay r = reference.ray(x, y, view, glm::dvec2(xi));
    maxAngle = std::max(maxAngle, test::angleBetween(glm::dvec3(d), r.dir));
    maxOrigin = std::max(maxOrigin, glm::length(glm::dvec3(o) - r.origin));
  };
  for (std::uint32_t view : {0u, layout.views() / 2, layout.views() - 1}) {
    for (std::uint32_t y = 0; y < layout.tileHeight; y += kQuiltStride)
      for (std::uint32_t x = 0; x < layout.tileWidth; x += kQuiltStride) check(x, y, view, glm::vec2(0.5f));
    for (std::uint32_t x : {0u, layout.tileWidth - 1})
      for (std::uint32_t y : {0u, layout.tileHeight - 1})
        for (glm::vec2 xi : {glm::vec2(0.0f), glm::vec2(0.9999999f)}) check(x, y, view, xi);
  }
  std::printf("quilt 8K float vs double: max angle %.3g rad, max origin %.3g (scene scale %.3g)\n", maxAngle, maxOrigin,
              sceneScale);
  EXPECT_LE(maxAngle, 2e-6);
  EXPECT_LE(maxOrigin, 1e-6 * sceneScale);
}

// View 0 is the leftmost camera (docs/OPTICS.md §4.1): origins move right with the view index; the centre pair
// straddles x=0.
TEST(QuiltModel, ViewsRunLeftToRight) {
  const DisplayConfig config = builtinDisplay("portrait");
  const QuiltLayout layout = defaultQuiltLayout(config);
  const gpu_shared::QuiltParams p = makeQuiltParams(config, test::testBounds(), layout);
  const LenticularCamera camera = resolveLenticularCamera(config, test::testBounds());
  float previous = -1e30f;
  for (std::uint32_t view = 0; view < layout.views(); ++view) {
    glm::vec3 o, d;
    gpu_shared::quilt_ray(p, 0, 0, view, glm::vec2(0.5f), o, d);
    EXPECT_GT(o.x, previous);
    previous = o.x;
    EXPECT_NEAR(o.z - camera.target.z, camera.focalDistance, 1e-5 * camera.focalDistance);
  }
}

}  // namespace
}  // namespace ht
