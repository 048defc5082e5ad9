// Hostile input: degenerate triangles are dropped and counted at build (CPU build and the GPU renderer's),
// without opening holes in what remains; every ray field set to NaN / +-Inf in turn misses in bounded steps
// on the CPU and the GPU (except tmax = +Inf, a valid unbounded ray); a BVH whose nodes all overlap one
// ray trips the step limit as an error, never as a silent miss.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "accuracy_test_util.h"
#include "bvh/cpu_traversal.h"
#include "common/error.h"
#include "gpu/renderer.h"
#include "interior_rays.h"
#include "test_meshes.h"

namespace ht::accuracy {
namespace {

using gpu_shared::HT_MISS;
using gpu_shared::HtRay;

// Appends one triangle with its own three vertices.
void addTriangle(TestMesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const auto base = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {a, b, c});
  mesh.triangles.emplace_back(base, base + 1, base + 2);
}

TEST(HostileInput, DegenerateTrianglesAreDroppedCountedAndLeaveNoHole) {
  const TestMesh clean = icosphere(3);
  TestMesh mesh = clean;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const glm::vec3 p(0.1f, 0.2f, 0.3f), q(0.4f, -0.2f, 0.1f);
  addTriangle(mesh, p, p, q);                                            // repeated vertex: zero area
  addTriangle(mesh, glm::vec3(0.5f), glm::vec3(1.0f), glm::vec3(2.0f));  // collinear: cross product exactly 0
  addTriangle(mesh, p, q, glm::vec3(nan, 0.0f, 0.0f));                   // NaN vertex
  addTriangle(mesh, p, q, glm::vec3(0.0f, inf, 0.0f));                   // Inf vertex
  addTriangle(mesh, p, q, glm::vec3(-inf, 0.0f, 0.0f));
  addTriangle(mesh, p, p, p);  // a point
  constexpr uint64_t kDegenerate = 6;
  // A needle (length 0.6, width 1e-7) has non-zero area: it is kept, and a ray across it must find it. (pbrt-v3's
  // float bound t > deltaT alone rejected this hit at t = 0.5; bvh/watertight_triangle.h rechecks in double.)
  addTriangle(mesh, glm::vec3(-0.3f, 0.0f, 0.0f), glm::vec3(0.3f, 0.0f, 0.0f), glm::vec3(0.3f, 1e-7f, 0.0f));
  const uint32_t needle = static_cast<uint32_t>(mesh.triangles.size() - 1);

  const bvh::GpuBvh cpu = bvh::buildGpuBvh(mesh.positions, mesh.triangles, bvh::BuildOptions{});
  EXPECT_EQ(cpu.report.trianglesDropped, kDegenerate);
  gpu::Renderer renderer(test::sharedContext(), toScene(mesh));
  EXPECT_EQ(renderer.bvhReport().trianglesDropped, kDegenerate);

  // The closed sphere is intact: no interior ray misses it (the needle lies inside, some rays hit it first).
  const auto rays = mixedInteriorRays(clean, test::scaledCount(50000), 21);
  const auto gpuHits = renderer.traceClosest(rays);
  const auto cpuHits = bvh::traceClosestBatch(cpu, rays);
  for (size_t i = 0; i < rays.size(); ++i) {
    ASSERT_NE(cpuHits[i].hit.triId, HT_MISS) << "ray " << i;
    ASSERT_NE(gpuHits[i].triId, HT_MISS) << "ray " << i;
  }
  // Down through the needle at x = 0.29, y = 0.9e-7 (inside: y < 1e-7 * (x + 0.3) / 0.6).
  const HtRay down{{0.29f, 0.9e-7f, 0.5f}, 0.0f, {0.0f, 0.0f, -1.0f}, 3.0e38f};
  EXPECT_EQ(bvh::traceClosest(cpu, down).hit.triId, needle);
  EXPECT_EQ(renderer.traceClosest(std::span(&down, 1))[0].triId, needle);
}

// Each of the 8 ray fields set to NaN, +Inf and -Inf in turn, on a ray that would otherwise hit.
// The last ray is the valid one (tmin = -Inf, tmax = +Inf).
std::vector<HtRay> poisonedRays() {
  const float values[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity()};
  const HtRay good{{0.0f, 0.0f, 0.0f}, 0.0f, {0.3f, 0.5f, 0.8f}, 3.0e38f};
  std::vector<HtRay> rays;
  for (int field = 0; field < 8; ++field) {
    for (float value : values) {
      HtRay r = good;
      float* slots[] = {&r.origin.x, &r.origin.y, &r.origin.z, &r.tmin, &r.dir.x, &r.dir.y, &r.dir.z, &r.tmax};
      *slots[field] = value;
      // Valid, checked apart: tmax = +Inf (unbounded ray) and tmin = -Inf (no lower bound; hits still need
      // t > 0 from the watertight test's deltaT, so it behaves as tmin = 0).
      if (field == 7 && value == std::numeric_limits<float>::infinity()) continue;
      if (field == 3 && value == -std::numeric_limits<float>::infinity()) continue;
      rays.push_back(r);
    }
  }
  rays.push_back(HtRay{{0.0f, 0.0f, 0.0f}, 0.0f, {0.0f, 0.0f, 0.0f}, 3.0e38f});  // zero direction
  HtRay unbounded = good;
  unbounded.tmin = -std::numeric_limits<float>::infinity();
  unbounded.tmax = std::numeric_limits<float>::infinity();
  rays.push_back(unbounded);
  return rays;
}

TEST(HostileInput, NanAndInfInEveryRayFieldMissInBoundedSteps) {
  const TestMesh mesh = icosphere(4);
  const auto rays = poisonedRays();
  const bvh::GpuBvh cpu = bvh::buildGpuBvh(mesh.positions, mesh.triangles, bvh::BuildOptions{});
  gpu::Renderer renderer(test::sharedContext(), toScene(mesh));
  gpu::TraceStats stats;
  const auto gpuHits = renderer.traceClosest(rays, &stats);
  const size_t poisoned = rays.size() - 1;
  for (size_t i = 0; i < poisoned; ++i) {
    const auto r = bvh::traceClosest(cpu, rays[i]);
    EXPECT_EQ(r.hit.triId, HT_MISS) << "ray " << i;
    EXPECT_LE(r.steps, 1u) << "ray " << i << ": a poisoned ray must be rejected before traversal";
    EXPECT_EQ(gpuHits[i].triId, HT_MISS) << "ray " << i;
  }
  HtRay bounded = rays.back();
  bounded.tmin = 0.0f;
  bounded.tmax = 3.0e38f;
  const auto expected = bvh::traceClosest(cpu, bounded).hit;
  ASSERT_NE(expected.triId, HT_MISS);
  EXPECT_EQ(bvh::traceClosest(cpu, rays.back()).hit.triId, expected.triId) << "tmin = -Inf, tmax = +Inf is valid";
  EXPECT_EQ(gpuHits.back().triId, expected.triId) << "tmin = -Inf, tmax = +Inf is valid";
  // The valid ray of an icosphere-s4 needs a few dozen steps; a poisoned ray looping would need thousands.
  EXPECT_LT(stats.maxSteps, 200u);
}

// 100,000 copies of one quad: every node's box contains the ray and every triangle hits at the same t, so
// closest-hit traversal cannot prune (an idea different from tests/gpu's sliver stack, whose triangles all
// miss). CPU: overflow flag with a small step limit; GPU: GpuError naming the step limit.
TEST(HostileInput, CoincidentTrianglesTripTheStepLimitAsAnError) {
  TestMesh mesh;
  mesh.name = "coincident";
  // Not scaled down under the sanitizers: the GPU half must exceed the step limit (60,000) for real; 20,000
  // coincident triangles take ~30,000 steps and legitimately finish.
  const uint32_t copies = 100000;
  for (uint32_t i = 0; i < copies; ++i) {
    addTriangle(mesh, {-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.0f});
  }
  const HtRay ray{{0.5f, -0.5f, 1.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, 3.0e38f};
  const bvh::GpuBvh cpu = bvh::buildGpuBvh(mesh.positions, mesh.triangles, bvh::BuildOptions{});
  const auto limited = bvh::traceClosest(cpu, ray, 1000);
  EXPECT_TRUE(limited.overflow);
  gpu::Renderer renderer(test::sharedContext(), toScene(mesh));
  EXPECT_THROW(renderer.traceClosest(std::span(&ray, 1)), GpuError);
}

}  // namespace
}  // namespace ht::accuracy
