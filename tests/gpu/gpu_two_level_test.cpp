// gpu_two_level_test.cpp - the GLSL build of the order-free two-level traversal (bvh/ordered_traversal.h, run by
// gpu/shaders/two_level_probe.comp) returns the CPU build's hits bit for bit: random instanced scenes, before and after
// random node moves (the CPU two-level hits equal the flattened BVH's, tests/bvh/bvh_two_level_test.cpp).
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "bvh/cpu_traversal.h"
#include "gpu/kernel_probe.h"
#include "tests/bvh/instanced_soup.h"
#include "tests/gpu/gpu_test_util.h"

namespace ht::gpu {
namespace {

using bvh::TwoLevelBvh;
using gpu_shared::HtTraceResult;

void expectGpuEqualsCpu(const TwoLevelBvh& twoLevel, const std::vector<gpu_shared::HtRay>& rays) {
  const std::vector<HtTraceResult> gpu = runTwoLevelProbe(test::sharedContext(), twoLevel, rays);
  ASSERT_EQ(gpu.size(), rays.size());
  uint32_t hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const HtTraceResult cpu = bvh::traceClosestTwoLevel(twoLevel, rays[i]);
    EXPECT_FALSE(gpu[i].overflow) << "ray " << i;
    EXPECT_EQ(std::memcmp(&gpu[i].hit, &cpu.hit, sizeof(cpu.hit)), 0)
        << "ray " << i << ": GPU (t " << gpu[i].hit.t << ", id " << gpu[i].hit.triId << ") vs CPU (t " << cpu.hit.t
        << ", id " << cpu.hit.triId << ")";
    EXPECT_EQ(gpu[i].steps, cpu.steps) << "ray " << i;
    hits += cpu.hit.triId != gpu_shared::HT_MISS;
  }
  EXPECT_GT(hits, rays.size() / 10);
}

TEST(GpuTwoLevelTest, GlslTraversalEqualsTheCppTraversalBitForBit) {
  std::mt19937 rng(21);
  bvh::test::InstancedSoup soup = bvh::test::randomScene(rng, 12);
  TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
  const std::vector<gpu_shared::HtRay> rays = bvh::test::randomRays(rng, soup, 4000);
  expectGpuEqualsCpu(twoLevel, rays);

  const std::vector<uint32_t> moved{3, 7};
  for (uint32_t m : moved) soup.place(m, bvh::test::randomPlacement(rng, true));
  twoLevel.updateInstances(soup.positions, soup.triangles, moved);
  expectGpuEqualsCpu(twoLevel, rays);
}

}  // namespace
}  // namespace ht::gpu
