// bvh_intersection_test.cpp - watertight triangle test vs the double oracle, watertightness on shared edges
// and vertices, conservative slab test, error constants.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "bvh/float_bounds.h"
#include "bvh/reference_intersect.h"
#include "bvh/slab_test.h"
#include "bvh/watertight_triangle.h"
#include "bvh_test_util.h"

namespace ht::bvh {
namespace {

using namespace gpu_shared;

struct FloatHit {
  bool hit;
  float t, u, v;
};

FloatHit intersect(const HtRay& ray, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  HtWatertightRay r = ht_make_watertight_ray(ray.origin, ray.dir, ray.tmin);
  FloatHit h{};
  h.hit = ht_intersect_triangle(r, a, b, c, ray.tmax, h.t, h.u, h.v);
  return h;
}

float nextUp(float x, int n) {
  for (int i = 0; i < n; ++i) x = std::nextafter(x, INFINITY);
  return x;
}

TEST(BvhConstants, ErrorBoundsMatchPbrtDefinitions) {
  const float eps = std::numeric_limits<float>::epsilon() * 0.5f;  // pbrt MachineEpsilon
  auto gamma = [eps](int n) { return (static_cast<float>(n) * eps) / (1.0f - static_cast<float>(n) * eps); };
  EXPECT_EQ(HT_MACHINE_EPSILON, eps);
  EXPECT_EQ(HT_GAMMA2, gamma(2));
  EXPECT_EQ(HT_GAMMA3, gamma(3));
  EXPECT_EQ(HT_GAMMA5, gamma(5));
  EXPECT_EQ(HT_SLAB_FAR_SCALE, 1.0f + 2.0f * gamma(3));
  EXPECT_EQ(HT_SLAB_FAR_SCALE, nextUp(1.0f, 3));  // = Embree's 1 + 3 ulp
  EXPECT_EQ(HT_FLOAT_MAX, std::numeric_limits<float>::max());
}

TEST(BvhWatertight, MatchesDoubleOracleOnRandomRays) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const uint32_t pairs = test::scaled(200000, 20000);
  uint32_t hits = 0;
  for (uint32_t i = 0; i < pairs; ++i) {
    glm::vec3 a(unit(rng), unit(rng), unit(rng)), b(unit(rng), unit(rng), unit(rng)),
        c(unit(rng), unit(rng), unit(rng));
    glm::vec3 origin = 3.0f * glm::vec3(unit(rng), unit(rng), unit(rng));
    // Aim near the triangle half of the time so that hits are frequent.
    glm::vec3 target = (a + b + c) / 3.0f + 0.3f * glm::vec3(unit(rng), unit(rng), unit(rng));
    HtRay ray = test::makeRay(origin, (i % 2 ? target - origin : test::randomUnitVector(rng)));
    FloatHit f = intersect(ray, a, b, c);
    ReferenceHit d = referenceIntersectTriangle(glm::dvec3(a), glm::dvec3(b), glm::dvec3(c), ray);
    ASSERT_EQ(f.hit, d.hit) << "pair " << i;
    if (!f.hit) continue;
    ++hits;
    // The float error of t is absolute, a few ulps of the magnitudes the test works with (the vertex
    // distances from the origin in units of |dir|; cf. pbrt's deltaT), not relative to t itself.
    double scale =
        std::max({glm::distance(a, origin), glm::distance(b, origin), glm::distance(c, origin)}) / glm::length(ray.dir);
    EXPECT_NEAR(f.t, d.t, 1e-5 * std::max(d.t, scale)) << "pair " << i;
    EXPECT_NEAR(f.u, d.u, 1e-4) << "pair " << i;
    EXPECT_NEAR(f.v, d.v, 1e-4) << "pair " << i;
  }
  EXPECT_GT(hits, pairs / 10);
}

TEST(BvhWatertight, RangeAndBackfaceSemantics) {
  const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  // Both windings hit.
  EXPECT_TRUE(intersect(test::makeRay({0.2f, 0.2f, 1}, {0, 0, -1}), a, b, c).hit);
  EXPECT_TRUE(intersect(test::makeRay({0.2f, 0.2f, -1}, {0, 0, 1}), a, b, c).hit);
  // t = 1 exactly: inside [tmin, tmax] inclusive, outside when tmax < 1 or tmin > 1.
  FloatHit h = intersect(test::makeRay({0.2f, 0.3f, 1}, {0, 0, -1}), a, b, c);
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.t, 1.0f);
  EXPECT_FLOAT_EQ(h.u, 0.2f);
  EXPECT_FLOAT_EQ(h.v, 0.3f);
  EXPECT_TRUE(intersect(test::makeRay({0.2f, 0.3f, 1}, {0, 0, -1}, 0.0f, 1.0f), a, b, c).hit);
  EXPECT_FALSE(intersect(test::makeRay({0.2f, 0.3f, 1}, {0, 0, -1}, 0.0f, 0.999f), a, b, c).hit);
  EXPECT_FALSE(intersect(test::makeRay({0.2f, 0.3f, 1}, {0, 0, -1}, 1.001f, 5.0f), a, b, c).hit);
  // Behind the origin, and origin on the triangle (t = 0): no hit (pbrt's t > deltaT).
  EXPECT_FALSE(intersect(test::makeRay({0.2f, 0.2f, 1}, {0, 0, 1}), a, b, c).hit);
  EXPECT_FALSE(intersect(test::makeRay({0.2f, 0.2f, 0}, {0, 0, 1}), a, b, c).hit);
  // Ray in the triangle's plane: det = 0, no hit.
  EXPECT_FALSE(intersect(test::makeRay({-1, 0.2f, 0}, {1, 0, 0}), a, b, c).hit);
}

// A fan of triangles around a centre vertex (irregular float coordinates, optionally far from the origin).
// Rays aimed at the interior spokes (shared edges) and at the centre (shared vertex) must hit at least one
// fan triangle: the property the double-precision fallback and shared vertex transforms guarantee.
void expectFanIsWatertight(glm::vec3 shift, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(0.7f, 1.3f), unit(-1.0f, 1.0f);
  const uint32_t spokes = 7;
  const glm::vec3 center = shift + glm::vec3(0.1234567f, -0.3456789f, 0.0987654f);
  std::vector<glm::vec3> rim;
  for (uint32_t k = 0; k < spokes; ++k) {
    double phi = 2.0 * std::numbers::pi * k / spokes;
    rim.push_back(center + glm::vec3(jitter(rng) * static_cast<float>(std::cos(phi)),
                                     jitter(rng) * static_cast<float>(std::sin(phi)), 0.3f * unit(rng)));
  }
  auto fanHit = [&](const HtRay& ray) {
    for (uint32_t k = 0; k < spokes; ++k) {
      if (intersect(ray, center, rim[k], rim[(k + 1) % spokes]).hit) return true;
    }
    return false;
  };
  const uint32_t raysPerTarget = test::scaled(2000, 300);
  uint32_t leaks = 0, total = 0;
  for (uint32_t k = 0; k <= spokes; ++k) {
    for (uint32_t i = 0; i < raysPerTarget; ++i) {
      // Target: the centre vertex (k == spokes) or a point on spoke k (rounded to float: within an ulp).
      float s = 0.05f + 0.9f * (unit(rng) * 0.5f + 0.5f);
      glm::vec3 target = k == spokes ? center : center + s * (rim[k] - center);
      glm::vec3 origin;
      glm::vec3 dir;
      switch (i % 3) {
        case 0:  // arbitrary direction from above or below
          origin = target + glm::vec3(unit(rng), unit(rng), unit(rng) > 0 ? 2.0f : -2.0f);
          dir = target - origin;
          break;
        case 1:  // axis-aligned ray along z (two zero direction components)
          origin = glm::vec3(target.x, target.y, target.z + 3.0f);
          dir = glm::vec3(0, 0, -1);
          break;
        default:  // direction in the xz plane (one zero component)
          origin = glm::vec3(target.x + unit(rng), target.y, target.z + 2.0f);
          dir = target - origin;
          dir.y = 0.0f;
          break;
      }
      ++total;
      if (!fanHit(test::makeRay(origin, dir))) ++leaks;
    }
  }
  EXPECT_EQ(leaks, 0u) << "of " << total << " rays through shared edges/vertex, shift " << shift.x;
}

TEST(BvhWatertight, SharedEdgesAndVertexOfFanNeverLeak) {
  expectFanIsWatertight(glm::vec3(0), 1);
  expectFanIsWatertight(glm::vec3(148376.0f, 1234.0f, -223423.0f), 2);  // Embree verify's far centre
  expectFanIsWatertight(glm::vec3(1e-3f), 3);
}

TEST(BvhWatertight, DoubleFallbackDecidesExactEdgeHits) {
  // Ray exactly through the shared edge x = y of two triangles: the float edge function is exactly 0 on both
  // and each triangle accepts the edge, so both report a hit.
  const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0);
  HtRay ray = test::makeRay({0.5f, 0.5f, 1}, {0, 0, -1});
  EXPECT_TRUE(intersect(ray, a, b, c).hit);
  EXPECT_TRUE(intersect(ray, a, c, d).hit);
}

TEST(BvhSlab, SafeReciprocalIsFiniteAndKeepsSign) {
  EXPECT_EQ(ht_safe_rcp(0.0f), 1e18f);
  EXPECT_EQ(ht_safe_rcp(-0.0f), -1e18f);
  EXPECT_EQ(ht_safe_rcp(1e-30f), 1e18f);
  EXPECT_EQ(ht_safe_rcp(-1e-40f), -1e18f);
  EXPECT_EQ(ht_safe_rcp(2.0f), 0.5f);
  EXPECT_EQ(ht_safe_rcp(-4.0f), -0.25f);
}

TEST(BvhSlab, NanOrderedMinMax) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(ht_min_nan(nan, 2.0f), 2.0f);
  EXPECT_EQ(ht_max_nan(nan, 2.0f), 2.0f);
  EXPECT_EQ(ht_min_nan(1.0f, 2.0f), 1.0f);
  EXPECT_EQ(ht_max_nan(1.0f, 2.0f), 2.0f);
}

GpuBvhNode nodeWithBoxes(glm::vec3 lo0, glm::vec3 hi0, glm::vec3 lo1, glm::vec3 hi1) {
  GpuBvhNode n;
  n.c0xy = glm::vec4(lo0.x, hi0.x, lo0.y, hi0.y);
  n.c1xy = glm::vec4(lo1.x, hi1.x, lo1.y, hi1.y);
  n.c01z = glm::vec4(lo0.z, hi0.z, lo1.z, hi1.z);
  n.link = glm::uvec4(0);
  return n;
}

TEST(BvhSlab, OriginOnSlabPlaneWithZeroDirectionComponent) {
  // Ray in the plane x = 0, direction x = +0 or -0: no 0 * inf NaN. With zero_fix semantics (1/(+-0) ->
  // +-1e18) a box whose NEAR plane (for the sign of the zero) holds the origin is entered over the full
  // interval; the box on the other side of that plane, for which it is the far plane, exits at t = 0.
  // So of two boxes sharing the plane exactly one is entered: a ray along a shared face is never lost.
  GpuBvhNode n = nodeWithBoxes({0, 0, 0}, {1, 1, 1}, {-1, 0, 0}, {0, 1, 1});
  for (float dx : {0.0f, -0.0f}) {
    HtSlabRay r = ht_make_slab_ray({0, 0.5f, -1}, {dx, 0, 1}, 0.0f);
    bool hit0, hit1;
    float t0, t1;
    ht_slab_node(r, n, INFINITY, hit0, hit1, t0, t1);
    EXPECT_TRUE(hit0 != hit1) << "dx sign " << std::signbit(dx);
    EXPECT_EQ(hit0, !std::signbit(dx));  // +0 moves towards +x: the box [0, 1] is entered
    EXPECT_EQ(hit0 ? t0 : t1, 1.0f);
  }
}

TEST(BvhSlab, EmptyBoxIsNeverEntered) {
  const float inf = INFINITY;
  GpuBvhNode n = nodeWithBoxes({inf, inf, inf}, {-inf, -inf, -inf}, {inf, inf, inf}, {-inf, -inf, -inf});
  std::mt19937 rng(5);
  for (int i = 0; i < 1000; ++i) {
    glm::vec3 dir = test::randomUnitVector(rng);
    if (i % 4 == 0) dir.x = 0.0f;
    if (i % 8 == 0) dir.y = -0.0f;
    HtSlabRay r = ht_make_slab_ray(3.0f * test::randomUnitVector(rng), dir, 0.0f);
    bool hit0, hit1;
    float t0, t1;
    ht_slab_node(r, n, inf, hit0, hit1, t0, t1);
    ASSERT_FALSE(hit0 || hit1);
  }
}

// A box that the exact (double) ray meets over an interval must not be culled by the float test.
TEST(BvhSlab, ConservativeAgainstDoubleSlabTest) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const uint32_t n = test::scaled(200000, 20000);
  uint32_t hits = 0;
  for (uint32_t i = 0; i < n; ++i) {
    glm::vec3 lo(unit(rng), unit(rng), unit(rng));
    glm::vec3 hi = lo + glm::abs(glm::vec3(unit(rng), unit(rng), unit(rng))) * (i % 5 == 0 ? 1e-6f : 0.5f);
    glm::vec3 origin = 4.0f * glm::vec3(unit(rng), unit(rng), unit(rng));
    glm::vec3 target = glm::mix(lo, hi, glm::vec3(unit(rng), unit(rng), unit(rng)) * 0.5f + 0.5f);
    glm::vec3 dir = target - origin;  // aims at a point inside (or, after rounding, on) the box
    // Exact interval in double.
    double tNear = 0.0, tFar = INFINITY;
    for (int k = 0; k < 3; ++k) {
      if (dir[k] == 0.0f) continue;
      double a = (double(lo[k]) - origin[k]) / dir[k], b = (double(hi[k]) - origin[k]) / dir[k];
      tNear = std::max(tNear, std::min(a, b));
      tFar = std::min(tFar, std::max(a, b));
    }
    bool exactHit = tNear <= tFar;
    GpuBvhNode node = nodeWithBoxes(lo, hi, lo, hi);
    HtSlabRay r = ht_make_slab_ray(origin, dir, 0.0f);
    bool hit0, hit1;
    float t0, t1;
    ht_slab_node(r, node, INFINITY, hit0, hit1, t0, t1);
    if (exactHit) {
      ++hits;
      ASSERT_TRUE(hit0 && hit1) << "float slab test culled a box the ray meets, case " << i;
    }
  }
  EXPECT_GT(hits, n / 2);
}

}  // namespace
}  // namespace ht::bvh
