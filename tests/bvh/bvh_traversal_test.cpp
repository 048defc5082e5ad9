// bvh_traversal_test.cpp - the shared traversal (bvh_traversal.h, run on the CPU) against brute force,
// step limit, invalid rays, any-hit, and leak-free closed meshes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "bvh/cpu_traversal.h"
#include "bvh/reference_intersect.h"
#include "bvh/watertight_triangle.h"
#include "bvh_test_util.h"

namespace ht::bvh {
namespace {

using gpu_shared::HT_MISS;

// Brute force over all triangles with the same float watertight test the traversal uses.
HtHit bruteForceFloat(const test::Mesh& mesh, const HtRay& ray) {
  HtHit best{ray.tmax, HT_MISS, 0.0f, 0.0f};
  gpu_shared::HtWatertightRay r = gpu_shared::ht_make_watertight_ray(ray.origin, ray.dir, ray.tmin);
  for (uint32_t id = 0; id < mesh.triangles.size(); ++id) {
    const glm::uvec3& tri = mesh.triangles[id];
    float t, u, v;
    if (gpu_shared::ht_intersect_triangle(r, mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z],
                                          best.t, t, u, v)) {
      best = HtHit{t, id, u, v};
    }
  }
  return best;
}

std::vector<HtRay> randomRays(uint32_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-0.5f, 1.5f);
  std::vector<HtRay> rays;
  for (uint32_t i = 0; i < n; ++i) {
    glm::vec3 origin(unit(rng), unit(rng), unit(rng));
    glm::vec3 dir = test::randomUnitVector(rng);
    if (i % 7 == 0) dir = glm::vec3(0, 0, (i % 2) ? 1.0f : -1.0f);  // axis-aligned
    rays.push_back(test::makeRay(origin, dir));
  }
  return rays;
}

// Traversal result vs the float brute force (same triangle test: identical hit/miss, t equal up to the
// last-ulp effect of testing against a shrinking tmax) and vs the double oracle (1e-6 relative).
void expectMatchesBruteForce(const test::Mesh& mesh, const std::vector<HtRay>& rays) {
  GpuBvh gpu = buildGpuBvh(mesh.positions, mesh.triangles, {});
  std::vector<HtTraceResult> results = traceClosestBatch(gpu, rays);
  uint32_t hits = 0, oracleMismatch = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const HtTraceResult& r = results[i];
    ASSERT_FALSE(r.overflow) << "ray " << i;
    HtHit brute = bruteForceFloat(mesh, rays[i]);
    ASSERT_EQ(r.hit.triId == HT_MISS, brute.triId == HT_MISS) << "ray " << i;
    ReferenceHit oracle = referenceClosestHit(mesh.positions, mesh.triangles, rays[i]);
    if (oracle.hit != (r.hit.triId != HT_MISS)) ++oracleMismatch;
    if (brute.triId == HT_MISS) continue;
    ++hits;
    EXPECT_NEAR(r.hit.t, brute.t, 1e-6 * brute.t) << "ray " << i;
    if (oracle.hit) {
      // Float t carries an absolute error of a few ulps of the vertex distances from the origin (in units
      // of |dir|), so for hits very close to the origin the tolerance is relative to that scale, not to t.
      const glm::uvec3& tri = mesh.triangles[oracle.triId];
      float scale = 0.0f;
      for (int k = 0; k < 3; ++k) scale = std::max(scale, glm::distance(mesh.positions[tri[k]], rays[i].origin));
      scale /= glm::length(rays[i].dir);
      EXPECT_NEAR(r.hit.t, oracle.t, 1e-6 * std::max<double>(oracle.t, scale)) << "ray " << i;
    }
    // Any-hit agrees on occlusion.
    HtTraceResult any = traceAny(gpu, rays[i]);
    EXPECT_NE(any.hit.triId, HT_MISS) << "ray " << i;
    EXPECT_LE(any.steps, r.steps) << "ray " << i;
  }
  EXPECT_EQ(oracleMismatch, 0u);
  EXPECT_GT(hits, rays.size() / 10);
}

TEST(BvhTraversal, MatchesBruteForceOnRandomSoups) {
  const uint32_t rays = test::scaled(2000, 300);
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    test::Mesh mesh = test::randomSoup(2000 * seed, 0.08f, seed);
    expectMatchesBruteForce(mesh, randomRays(rays, 100 + seed));
  }
}

TEST(BvhTraversal, MatchesBruteForceOnBunny) {
  test::Mesh bunny = test::loadObj(test::kBunnyPath);
  if (bunny.triangles.empty()) GTEST_SKIP() << test::kBunnyPath << " not found";
  std::vector<HtRay> all = test::pinholeRays(bunny, 64, 64);
  std::vector<HtRay> rays;
  const uint32_t stride = test::scaled(8, 41);
  for (size_t i = 0; i < all.size(); i += stride) rays.push_back(all[i]);
  expectMatchesBruteForce(bunny, rays);
}

TEST(BvhTraversal, AnyHitRespectsTmax) {
  test::Mesh mesh;
  mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  GpuBvh gpu = buildGpuBvh(mesh.positions, mesh.triangles, {});
  EXPECT_NE(traceAny(gpu, test::makeRay({0, 0, 2}, {0, 0, -1}, 0.0f, 2.0f)).hit.triId, HT_MISS);
  EXPECT_EQ(traceAny(gpu, test::makeRay({0, 0, 2}, {0, 0, -1}, 0.0f, 1.99f)).hit.triId, HT_MISS);
  EXPECT_EQ(traceAny(gpu, test::makeRay({0, 0, 2}, {0, 0, -1}, 2.01f, 5.0f)).hit.triId, HT_MISS);
  HtTraceResult closest = traceClosest(gpu, test::makeRay({0, 0, 2}, {0, 0, -1}));
  EXPECT_EQ(closest.hit.t, 2.0f);
  EXPECT_EQ(closest.hit.triId, 0u);
}

TEST(BvhTraversal, EmptyAndDefaultBvhMiss) {
  GpuBvh empty = buildGpuBvh({}, {}, {});
  HtRay ray = test::makeRay({0, 0, 0}, {0, 0, 1});
  HtTraceResult r = traceClosest(empty, ray);
  EXPECT_EQ(r.hit.triId, HT_MISS);
  EXPECT_FALSE(r.overflow);
  EXPECT_EQ(traceClosest(GpuBvh{}, ray).hit.triId, HT_MISS);
}

// A step limit below what a ray needs must set overflow; a result without overflow must equal the
// unlimited one. A truncated traversal is therefore never reported as a silent miss.
TEST(BvhTraversal, StepLimitReportsOverflowNeverSilentMiss) {
  test::Mesh bunny = test::loadObj(test::kBunnyPath);
  if (bunny.triangles.empty()) GTEST_SKIP() << test::kBunnyPath << " not found";
  GpuBvh gpu = buildGpuBvh(bunny.positions, bunny.triangles, {});
  std::vector<HtRay> rays = test::pinholeRays(bunny, 48, 48);
  uint32_t overflows = 0;
  for (const HtRay& ray : rays) {
    HtTraceResult full = traceClosest(gpu, ray);
    ASSERT_FALSE(full.overflow);
    for (uint32_t limit : {0u, 1u, 3u, 10u, 30u, full.steps - 1, full.steps}) {
      if (limit > full.steps) continue;
      HtTraceResult limited = traceClosest(gpu, ray, limit);
      if (limit < full.steps) {
        ASSERT_TRUE(limited.overflow) << "limit " << limit << " of " << full.steps;
        ++overflows;
      } else {
        ASSERT_FALSE(limited.overflow);
        ASSERT_EQ(limited.hit.triId, full.hit.triId);
        ASSERT_EQ(limited.hit.t, full.hit.t);
      }
      ASSERT_LE(limited.steps, limit + 1);
      HtTraceResult any = traceAny(gpu, ray, limit);
      ASSERT_TRUE(any.overflow || any.hit.triId == traceAny(gpu, ray).hit.triId);
    }
  }
  EXPECT_GT(overflows, rays.size());
}

TEST(BvhTraversal, NanAndInfRaysMissImmediately) {
  test::Mesh mesh = test::randomSoup(1000, 0.1f, 5);
  GpuBvh gpu = buildGpuBvh(mesh.positions, mesh.triangles, {});
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = INFINITY;
  std::vector<HtRay> bad = {
      test::makeRay({nan, 0.5f, 0.5f}, {0, 0, 1}),        test::makeRay({0.5f, 0.5f, 0.5f}, {nan, 0, 1}),
      test::makeRay({inf, 0.5f, 0.5f}, {-1, 0, 0}),       test::makeRay({0.5f, -inf, 0.5f}, {0, 1, 0}),
      test::makeRay({0.5f, 0.5f, -2}, {0, 0, inf}),       test::makeRay({0.5f, 0.5f, -2}, {inf, inf, inf}),
      test::makeRay({0.5f, 0.5f, -2}, {0, 0, 0}),         test::makeRay({0.5f, 0.5f, -2}, {0, 0, 1}, nan, inf),
      test::makeRay({0.5f, 0.5f, -2}, {0, 0, 1}, 0, nan), test::makeRay({0.5f, 0.5f, -2}, {0, 0, 1}, 5, 1),
  };
  for (size_t i = 0; i < bad.size(); ++i) {
    for (HtTraceResult r : {traceClosest(gpu, bad[i]), traceAny(gpu, bad[i])}) {
      EXPECT_EQ(r.hit.triId, HT_MISS) << "ray " << i;
      EXPECT_EQ(r.steps, 0u) << "ray " << i;
      EXPECT_FALSE(r.overflow) << "ray " << i;
    }
  }
  // tmax = +inf and a huge but finite origin are valid.
  HtTraceResult ok = traceClosest(gpu, test::makeRay({0.5f, 0.5f, -3e38f}, {0, 0, 1}));
  EXPECT_GT(ok.steps, 0u);
  EXPECT_FALSE(ok.overflow);
}

// Embree verify's watertight test (docs/BVH.md §6): rays from inside a closed sphere centred far from the origin
// must all hit; here also near the origin and for axis-aligned directions.
TEST(BvhTraversal, ClosedSphereDoesNotLeak) {
  const uint32_t rays = test::scaled(200000, 20000);
  for (glm::vec3 center : {glm::vec3(0.25f, -0.5f, 0.125f), glm::vec3(148376.0f, 1234.0f, -223423.0f)}) {
    test::Mesh sphere = test::closedSphere(center, 2.0f, 100, 200);
    GpuBvh gpu = buildGpuBvh(sphere.positions, sphere.triangles, {});
    // Far from the origin the polar triangles collapse to zero area in float and are dropped; their
    // neighbours then share the collapsed edges, so the surface stays closed.
    ASSERT_LT(gpu.report.trianglesDropped, sphere.triangles.size() / 100);
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<HtRay> batch;
    for (uint32_t i = 0; i < rays; ++i) {
      glm::vec3 origin = center + 1.5f * glm::vec3(unit(rng), unit(rng), unit(rng)) / std::sqrt(3.0f);
      glm::vec3 dir = test::randomUnitVector(rng);
      if (i % 5 == 0) dir = glm::vec3(0, (i % 2) ? -1.0f : 1.0f, 0);
      if (i % 5 == 1) dir.x = 0.0f;
      batch.push_back(test::makeRay(origin, dir));
    }
    std::vector<HtTraceResult> results = traceClosestBatch(gpu, batch);
    uint32_t leaks = 0;
    for (const HtTraceResult& r : results) leaks += (r.hit.triId == HT_MISS || r.overflow) ? 1 : 0;
    EXPECT_EQ(leaks, 0u) << "of " << rays << " rays, centre x " << center.x;
  }
}

// A watertight grid hit by axis-aligned rays exactly through vertex coordinates (edges and vertices shared
// by up to six triangles, origins on box planes): every ray hits.
TEST(BvhTraversal, AxisAlignedRaysThroughGridEdgesAndVertices) {
  test::Mesh grid;
  const uint32_t n = 32;
  for (uint32_t y = 0; y <= n; ++y) {
    for (uint32_t x = 0; x <= n; ++x) grid.positions.emplace_back(0.125f * x, 0.125f * y, 0.0f);
  }
  for (uint32_t y = 0; y < n; ++y) {
    for (uint32_t x = 0; x < n; ++x) {
      uint32_t i = y * (n + 1) + x;
      grid.triangles.emplace_back(i, i + 1, i + n + 2);
      grid.triangles.emplace_back(i, i + n + 2, i + n + 1);
    }
  }
  GpuBvh gpu = buildGpuBvh(grid.positions, grid.triangles, {});
  uint32_t misses = 0, total = 0;
  for (uint32_t y = 1; y < 2 * n; ++y) {  // interior only: half-cell steps hit edges, vertices, diagonals
    for (uint32_t x = 1; x < 2 * n; ++x) {
      for (float dz : {-1.0f, 1.0f}) {
        HtRay ray = test::makeRay({0.0625f * x, 0.0625f * y, -dz}, {0.0f, 0.0f, dz});
        ++total;
        if (traceClosest(gpu, ray).hit.triId == HT_MISS) ++misses;
        ray.dir = glm::vec3(-0.0f, -0.0f, dz);
        ++total;
        if (traceClosest(gpu, ray).hit.triId == HT_MISS) ++misses;
      }
    }
  }
  EXPECT_EQ(misses, 0u) << "of " << total;
}

}  // namespace
}  // namespace ht::bvh
