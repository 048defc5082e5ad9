// primary_ray_batch.cpp - see primary_ray_batch.h. Rays come from the renderer's own pinhole model
// (camera_models/pinhole_model.h), so the benchmark traces what `render` would for a pinhole display.
#include "bench/primary_ray_batch.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "camera_models/pinhole_model.h"

namespace ht::bench {
namespace {

constexpr float kFovyRadians = 0.7853982f;  // 45 degrees

gpu_shared::PinholeParams frameBounds(const Bounds3& bounds, std::uint32_t size) {
  const glm::vec3 centre = bounds.center();
  const glm::vec3 extent = bounds.extent();
  const float tanHalf = std::tan(0.5f * kFovyRadians);
  // Distance at which the larger of the x/y half extents fills the field of view, from the front face.
  const float halfSize = 0.5f * std::max(extent.x, extent.y);
  const float distance = 0.5f * extent.z + halfSize / tanHalf;
  const glm::vec3 eye = centre + glm::vec3(0.0f, 0.0f, distance);
  gpu_shared::PinholeParams params{};
  params.cameraToWorld = glm::inverse(glm::lookAt(eye, centre, glm::vec3(0.0f, 1.0f, 0.0f)));
  params.lens = glm::vec4(tanHalf, 1.0f, float(size), float(size));
  return params;
}

}  // namespace

RayBatch makePinholeRays(const Bounds3& bounds, std::uint32_t size) {
  RayBatch batch{size, size, {}};
  batch.rays.reserve(std::size_t(size) * size);
  const gpu_shared::PinholeParams params = frameBounds(bounds, size);
  for (std::uint32_t y = 0; y < size; ++y) {
    for (std::uint32_t x = 0; x < size; ++x) {
      gpu_shared::HtRay ray{};
      gpu_shared::pinhole_ray(params, x, y, glm::vec2(0.5f, 0.5f), ray.origin, ray.dir);
      ray.tmin = 0.0f;
      ray.tmax = std::numeric_limits<float>::max();
      batch.rays.push_back(ray);
    }
  }
  return batch;
}

}  // namespace ht::bench
