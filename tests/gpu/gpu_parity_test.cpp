// GPU vs CPU parity: the Vulkan kernels and the CPU reference run the same shared traversal and watertight
// triangle code (bvh/*.h), so on the same BVH and rays they must agree on hit/miss exactly and on t to
// within float reordering (|dt| <= 1e-5 relative).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "bvh/cpu_traversal.h"
#include "bvh/gpu_layout.h"
#include "gpu_test_util.h"

namespace ht::test {
namespace {

struct ParityCounts {
  size_t hits = 0, hitMissDisagreements = 0, tDisagreements = 0, triangleDifferences = 0;
  double maxRelDt = 0.0;
};

ParityCounts compare(const std::vector<gpu_shared::HtHit>& gpu, const std::vector<gpu_shared::HtTraceResult>& cpu) {
  ParityCounts c;
  for (size_t i = 0; i < gpu.size(); ++i) {
    bool gpuHit = gpu[i].triId != gpu_shared::HT_MISS, cpuHit = cpu[i].hit.triId != gpu_shared::HT_MISS;
    if (gpuHit != cpuHit) {
      if (c.hitMissDisagreements++ < 5)
        std::printf("  ray %zu: gpu %s, cpu %s\n", i, gpuHit ? "hit" : "miss", cpuHit ? "hit" : "miss");
      continue;
    }
    if (!gpuHit) continue;
    ++c.hits;
    if (gpu[i].triId != cpu[i].hit.triId) ++c.triangleDifferences;
    double rel = std::abs(double(gpu[i].t) - double(cpu[i].hit.t)) / std::max(1e-30, std::abs(double(cpu[i].hit.t)));
    c.maxRelDt = std::max(c.maxRelDt, rel);
    if (rel > 1e-5) ++c.tDisagreements;
  }
  return c;
}

class GpuParity : public ::testing::Test {
 protected:
  void SetUp() override {
    bunny_ = loadBunnyOrEmpty();
    if (bunny_.triangles.empty()) GTEST_SKIP() << "glmark2-data not installed (/usr/share/glmark2/models/bunny.obj)";
  }
  Scene bunny_;
};

TEST_F(GpuParity, ClosestHitMatchesCpuReferenceOnBunny) {
  const std::uint32_t size = kSanitized ? 256 : 1024;  // 1,048,576 rays in the Release suite
  Bounds3 b = bunny_.bounds();
  glm::vec3 c = b.center();
  float radius = glm::length(b.extent()) * 0.5f;
  auto cam = lookAt(c + glm::vec3(0.3f, 0.2f, 1.0f) * (2.2f * radius), c, 45.0f, size, size);
  std::vector<gpu_shared::HtRay> rays = pinholeRays(cam);

  gpu::Renderer renderer(sharedContext(), bunny_);
  gpu::TraceStats stats;
  std::vector<gpu_shared::HtHit> gpuHits = renderer.traceClosest(rays, &stats);

  bvh::GpuBvh cpuBvh = bvh::buildGpuBvh(bunny_.positions, bunny_.triangles, bvh::BuildOptions{});
  std::vector<gpu_shared::HtTraceResult> cpuHits(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) cpuHits[i] = bvh::traceClosest(cpuBvh, rays[i]);

  ParityCounts p = compare(gpuHits, cpuHits);
  std::printf("parity: %zu rays, %zu hits, max |dt|/t = %.3g, triangle ids differing %zu, GPU %.1f ms, max steps %u\n",
              rays.size(), p.hits, p.maxRelDt, p.triangleDifferences, stats.gpuMs, stats.maxSteps);
  EXPECT_GT(p.hits, rays.size() / 10) << "camera should see the bunny";
  EXPECT_EQ(p.hitMissDisagreements, 0u);
  EXPECT_EQ(p.tDisagreements, 0u);
  EXPECT_LE(p.maxRelDt, 1e-5);
}

TEST_F(GpuParity, AnyHitMatchesCpuReferenceOnBunny) {
  const std::uint32_t size = kSanitized ? 128 : 512;
  Bounds3 b = bunny_.bounds();
  glm::vec3 c = b.center();
  float radius = glm::length(b.extent()) * 0.5f;
  auto cam = lookAt(c + glm::vec3(-0.5f, 0.4f, 1.0f) * (2.0f * radius), c, 40.0f, size, size);
  std::vector<gpu_shared::HtRay> rays = pinholeRays(cam);
  // Shorten half of the rays so that some end before the surface: occlusion must respect tmax.
  for (size_t i = 0; i < rays.size(); i += 2) rays[i].tmax = 2.0f * radius;

  gpu::Renderer renderer(sharedContext(), bunny_);
  std::vector<std::uint32_t> gpuOccluded = renderer.traceOccluded(rays);
  bvh::GpuBvh cpuBvh = bvh::buildGpuBvh(bunny_.positions, bunny_.triangles, bvh::BuildOptions{});
  size_t disagreements = 0, occluded = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    bool cpu = bvh::traceAny(cpuBvh, rays[i]).hit.triId != gpu_shared::HT_MISS;
    occluded += cpu;
    disagreements += (gpuOccluded[i] != 0) != cpu;
  }
  EXPECT_GT(occluded, rays.size() / 20);
  EXPECT_EQ(disagreements, 0u);
}

// Coincident copies of one sphere: every hit is a tie of equal t between triangle k and its copy k + n. The kernel's
// closest hit is the least (t, triangle id) (bvh/ordered_traversal.h), so it must report the first copy on every ray,
// whatever the BVH's order, and equal the CPU reference bit for bit.
TEST(GpuOrderFreeHit, TiesResolveToTheLeastTriangleIdBitForBit) {
  Scene s;
  const std::uint32_t material = addMaterial(s, Material{});
  addIcosphere(s, glm::vec3(0.0f), 0.5f, 2, material);
  const auto n = static_cast<std::uint32_t>(s.triangles.size());
  addIcosphere(s, glm::vec3(0.0f), 0.5f, 2, material);
  auto cam = lookAt(glm::vec3(0.4f, 0.3f, 2.0f), glm::vec3(0.0f), 40.0f, 96, 96);
  std::vector<gpu_shared::HtRay> rays = pinholeRays(cam);

  gpu::Renderer renderer(sharedContext(), s);
  std::vector<gpu_shared::HtHit> gpuHits = renderer.traceClosest(rays);
  bvh::GpuBvh cpuBvh = bvh::buildGpuBvh(s.positions, s.triangles, bvh::BuildOptions{});
  size_t hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const gpu_shared::HtHit cpu = bvh::traceClosest(cpuBvh, rays[i]).hit;
    ASSERT_EQ(std::memcmp(&gpuHits[i], &cpu, sizeof cpu), 0) << "ray " << i;
    if (cpu.triId == gpu_shared::HT_MISS) continue;
    ++hits;
    ASSERT_LT(cpu.triId, n) << "ray " << i << ": a tie must resolve to the first copy";
  }
  EXPECT_GT(hits, rays.size() / 10);
}

}  // namespace
}  // namespace ht::test
