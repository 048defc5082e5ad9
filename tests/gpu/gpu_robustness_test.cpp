// The lavapipe loop cap and hostile rays: overflow must be an error, never a silent miss; NaN rays end.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "common/error.h"
#include "gpu_test_util.h"

namespace ht::test {
namespace {

// 200,000 thin diagonal slivers stacked in z. Every sliver's bounding box contains the line x = y = 0 but no
// sliver does, so a ray down that line must visit every node of the BVH: far more than the step limit.
Scene pathologicalSlivers(int count) {
  Scene s;
  s.name = "test:slivers";
  std::uint32_t m = addMaterial(s, Material{});
  for (int i = 0; i < count; ++i) {
    float z = -1.0f + 2.0f * static_cast<float>(i) / static_cast<float>(count);
    auto base = static_cast<std::uint32_t>(s.positions.size());
    s.positions.push_back({-1.0f, -0.5f, z});
    s.positions.push_back({0.5f, 1.0f, z});
    s.positions.push_back({-1.0f, -0.45f, z});
    s.triangles.push_back({base, base + 1, base + 2});
    s.triangleMaterial.push_back(m);
  }
  return s;
}

TEST(GpuRobustness, StepLimitOverflowIsReportedNotDropped) {
  Scene scene = pathologicalSlivers(200000);
  gpu::Renderer renderer(sharedContext(), scene);
  std::vector<gpu_shared::HtRay> rays(64, gpu_shared::HtRay{{0.0f, 0.0f, 5.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, 3.0e38f});
  try {
    gpu::TraceStats stats;
    auto hits = renderer.traceClosest(rays, &stats);
    FAIL() << "a ray visiting every node must trip the traversal step limit; max steps " << stats.maxSteps << ", hit "
           << hits[0].triId << " bvh " << renderer.bvhReport().summary();
  } catch (const GpuError& e) { EXPECT_NE(std::string(e.what()).find("step limit"), std::string::npos) << e.what(); }
  // An ordinary ray beside the slivers is fine on the same renderer.
  std::vector<gpu_shared::HtRay> ok(1, gpu_shared::HtRay{{5.0f, 5.0f, 5.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, 3.0e38f});
  EXPECT_EQ(renderer.traceClosest(ok)[0].triId, gpu_shared::HT_MISS);
}

TEST(GpuRobustness, NanAndInfRaysMissQuickly) {
  Scene scene = loadBunnyOrEmpty();
  if (scene.triangles.empty()) GTEST_SKIP() << "glmark2-data not installed";
  gpu::Renderer renderer(sharedContext(), scene);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  glm::vec3 c = scene.bounds().center();
  std::vector<gpu_shared::HtRay> rays = {
      {{nan, c.y, 1.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, 3e38f}, {{c.x, c.y, 1.0f}, 0.0f, {nan, 0.0f, -1.0f}, 3e38f},
      {{inf, c.y, 1.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, 3e38f}, {{c.x, c.y, 1.0f}, 0.0f, {0.0f, inf, -1.0f}, 3e38f},
      {{c.x, c.y, 1.0f}, 0.0f, {0.0f, 0.0f, 0.0f}, 3e38f},  {{c.x, c.y, 1.0f}, nan, {0.0f, 0.0f, -1.0f}, nan}};
  gpu::TraceStats stats;
  auto hits = renderer.traceClosest(rays, &stats);
  for (size_t i = 0; i < hits.size(); ++i) EXPECT_EQ(hits[i].triId, gpu_shared::HT_MISS) << "ray " << i;
  EXPECT_LT(stats.maxSteps, 1000u);
}

TEST(GpuRobustness, ValidationLayerIsCleanOnAFrame) {
  std::unique_ptr<gpu::VulkanContext> context;
  try {
    context = std::make_unique<gpu::VulkanContext>(gpu::VulkanContext::Options{-1, true});
  } catch (const GpuError& e) { GTEST_SKIP() << e.what(); }
  Scene scene = loadScene("builtin:showcase");
  {
    gpu::Renderer renderer(*context, scene);
    Bounds3 b = scene.bounds();
    auto cam = lookAt(b.center() + glm::vec3(0.0f, 0.5f, 2.0f) * glm::length(b.extent()), b.center(), 35.0f, 64, 48);
    gpu::RenderSettings settings;
    settings.spp = 1;
    renderer.renderPinhole(cam, settings);
    renderer.traceOccluded(std::vector<gpu_shared::HtRay>(8, gpu_shared::HtRay{b.center(), 0.0f, {0, -1, 0}, 1e30f}));
  }
  EXPECT_EQ(context->validationMessageCount(), 0u);
}

}  // namespace
}  // namespace ht::test
