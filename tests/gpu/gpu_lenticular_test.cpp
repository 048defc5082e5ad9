// The lenticular panel path end to end against an independent double-precision model: every subpixel of the
// Portrait panel traced on the GPU (raygen -> trace -> shade -> resolve -> interleave) must show the sphere
// exactly when the reference ray of that subpixel meets the sphere.
#include <gtest/gtest.h>

#include <cmath>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/lenticular_reference.h"
#include "gpu_test_util.h"

namespace ht::test {
namespace {

// Distance from the sphere centre (origin) to the line of a unit-direction ray, or +inf if the closest point
// is behind the origin of the ray.
double missDistance(const ReferenceRay& r) {
  double along = -glm::dot(r.origin, r.dir);
  if (along < 0.0) return INFINITY;
  return glm::length(r.origin + along * r.dir);
}

TEST(GpuLenticular, PortraitSubpixelsShowTheSphereExactlyWhereTheReferenceRaysHitIt) {
  const float radius = 0.5f;
  Scene scene;
  scene.background = glm::vec3(0.0f);
  scene.ambient = glm::vec3(0.0f);
  Material white;
  white.baseColor = glm::vec3(0.0f);
  white.emissive = glm::vec3(1.0f);
  addIcosphere(scene, glm::vec3(0.0f), radius, kSanitized ? 4 : 6, addMaterial(scene, white));
  // Inradius of the tessellation: rays passing between it and the radius may go either way.
  float inner = radius;
  for (const auto& t : scene.triangles) {
    glm::vec3 a = scene.positions[t.x], b = scene.positions[t.y], c = scene.positions[t.z];
    inner = std::min(inner, std::abs(glm::dot(glm::normalize(glm::cross(b - a, c - a)), a)));
  }

  DisplayConfig display = builtinDisplay("portrait");
  Bounds3 bounds = scene.bounds();
  gpu_shared::LenticularParams params = makeLenticularParams(display, bounds);
  LenticularReference reference(display, bounds);
  gpu::Renderer renderer(sharedContext(), scene);
  gpu::RenderSettings settings;
  settings.spp = 1;  // the footprint centre: the vendor's sample point
  gpu::RenderResult image = renderer.renderLenticular(params, settings);
  const std::uint32_t w = image.width, h = image.height;
  ASSERT_EQ(w, 1536u);
  ASSERT_EQ(h, 2048u);

  size_t covered = 0, expected = 0, ambiguous = 0, wrong = 0;
  const std::uint32_t stride = kSanitized ? 16 : 1;
  size_t tested = 0;
  for (std::uint32_t y = 0; y < h; y += stride) {
    for (std::uint32_t x = 0; x < w; ++x) {
      for (std::uint32_t c = 0; c < 3; ++c) {
        ++tested;
        double miss = missDistance(reference.ray(x, y, c, glm::dvec2(0.5)));
        float value = image.rgba[(static_cast<size_t>(h - 1 - y) * w + x) * 4 + c];
        bool gpuHit = value > 0.5f;
        covered += gpuHit;
        expected += miss < radius;
        if (miss >= inner * (1.0 - 1e-5) && miss <= radius * (1.0 + 1e-5)) {
          ++ambiguous;  // inside the tessellation band
        } else if (gpuHit != (miss < radius)) {
          ++wrong;
        }
      }
    }
  }
  std::printf("subpixels %zu, covered %zu, exact sphere %zu, in tessellation band %zu\n", tested, covered, expected,
              ambiguous);
  EXPECT_GT(expected, tested / 20);
  EXPECT_EQ(wrong, 0u);
  EXPECT_LE(std::abs(static_cast<double>(covered) - static_cast<double>(expected)), static_cast<double>(ambiguous));
}

}  // namespace
}  // namespace ht::test
