// display_model_render_test.cpp - every row of the display-model registry (camera_models/display_model_registry.h)
// through the GPU: the row's example display, set up around a small scene, renders a frame of its shape with finite
// pixels that see the scene, and raygen writes finite rays for it. A model whose GPU side is missing (no raygen
// branch, no block written, wrong shape) fails here.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "camera_models/display_model_registry.h"
#include "gpu_test_util.h"

namespace ht::test {
namespace {

constexpr std::uint64_t kMaxRenderedTargets = 1u << 16;  // larger examples (the device quilt) generate rays only
constexpr std::uint32_t kRayTargets = 64;

Scene registryScene() {
  Scene s;
  Material white;
  white.baseColor = glm::vec3(0.9f);
  addIcosphere(s, glm::vec3(0.0f), 0.5f, 2, addMaterial(s, white));
  s.ambient = glm::vec3(1.0f);
  return s;
}

TEST(DisplayModelRender, EveryRegistryRowRendersOnTheGpu) {
  const Scene scene = registryScene();
  gpu::Renderer renderer(sharedContext(), scene);
  for (const DisplayModelRow& row : displayModels()) {
    SCOPED_TRACE(std::string(row.name));
    const DisplayConfig config = parseDisplayConfig(row.example, "example", HT_TEST_DATA_DIR);
    const FrameCamera camera = row.makeCamera(config, scene.bounds(), testRayTable());
    const FrameShape shape = frameShape(camera);
    gpu::RenderSettings settings;
    settings.spp = 1;

    const std::uint32_t count = static_cast<std::uint32_t>(std::min<std::uint64_t>(kRayTargets, shape.targets()));
    const std::vector<gpu_shared::HtRay> rays = renderer.generateRays(camera, settings, 0, count);
    ASSERT_EQ(rays.size(), count);
    for (const gpu_shared::HtRay& ray : rays) {
      const glm::vec3 o(ray.origin), d(ray.dir);
      ASSERT_TRUE(std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z));
      ASSERT_TRUE(std::isfinite(glm::length(d)) && glm::length(d) > 0.0f);
    }
    if (shape.targets() > kMaxRenderedTargets) continue;

    const gpu::RenderResult frame = renderer.render(camera, settings);
    EXPECT_EQ(frame.width, shape.width);
    EXPECT_EQ(frame.height, shape.height);
    EXPECT_EQ(frame.views, shape.views);
    ASSERT_EQ(frame.rgba.size(), std::size_t(shape.width) * shape.height * shape.views * 4);
    EXPECT_EQ(frame.nonFiniteSamples, 0u);
    float brightest = 0.0f;
    for (float value : frame.rgba) brightest = std::max(brightest, value);
    EXPECT_GT(brightest, 0.1f) << "no view of " << row.name << " sees the lit sphere";
  }
}

}  // namespace
}  // namespace ht::test
