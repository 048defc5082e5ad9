// Determinism of the lenticular panel path: the same frame rendered twice on the same device is bit-identical
// (docs/PIPELINE.md "Determinism"; tests/gpu checks the pinhole path). The scene has a light (shadow rays and
// the ordered gather), a mirror (the ping-pong bounce queues filled by atomics) and spp = 1 (10 s at spp = 2 on
// lavapipe, too long for CI).
#include <gtest/gtest.h>

#include <cstring>

#include "accuracy_test_util.h"
#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "gpu/renderer.h"
#include "scene/mesh_generators.h"

namespace ht::accuracy {
namespace {

Scene litMirrorScene() {
  Scene s;
  s.name = "test:determinism";
  Material diffuse;
  diffuse.baseColor = glm::vec3(0.7f, 0.5f, 0.3f);
  Material mirror;
  mirror.metallic = 1.0f;
  mirror.roughness = 0.0f;
  makeIcosphere(s, glm::vec3(-0.3f, 0.0f, 0.0f), 0.35f, 4, addMaterial(s, diffuse));
  makeIcosphere(s, glm::vec3(0.35f, 0.1f, -0.2f), 0.3f, 3, addMaterial(s, mirror));
  makeQuad(s, glm::vec3(0.0f, -0.4f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f),
           addMaterial(s, diffuse));
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  sun.intensity = 2.0f;
  s.lights.push_back(sun);
  return s;
}

TEST(Determinism, LenticularPanelFrameTwiceIsBitIdentical) {
  const Scene scene = litMirrorScene();
  const DisplayConfig display = builtinDisplay("portrait");
  const auto params = makeLenticularParams(display, scene.bounds());
  gpu::Renderer renderer(test::sharedContext(), scene);
  gpu::RenderSettings settings;
  settings.spp = 1;
  const gpu::RenderResult a = renderer.renderLenticular(params, settings);
  const gpu::RenderResult b = renderer.renderLenticular(params, settings);
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  ASSERT_FALSE(a.rgba.empty());
  EXPECT_EQ(std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)), 0);
  EXPECT_EQ(a.nonFiniteSamples, 0u);
  // The frame is not trivially constant: some subpixels see the lit sphere, others the background.
  float lo = a.rgba[0], hi = a.rgba[0];
  for (float v : a.rgba) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_LT(lo, hi);
}

}  // namespace
}  // namespace ht::accuracy
