// ray_sets.cpp - see ray_sets.h.
#include "bench/ray_sets.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>

#include "bench/primary_ray_batch.h"
#include "bvh/offset_ray.h"

namespace ht::bench {
namespace {

using gpu_shared::HtHit;
using gpu_shared::HtRay;
constexpr std::uint32_t kTile = 16;
constexpr float kFloatMax = std::numeric_limits<float>::max();

// PCG-style integer hash -> float in [0, 1): deterministic per (ray, dimension, seed).
float hashToUnit(std::uint32_t a, std::uint32_t b, std::uint32_t seed) {
  std::uint32_t h = a * 747796405u + b * 2891336453u + seed * 277803737u + 1u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return float(h >> 8) * (1.0f / 16777216.0f);
}

struct SurfacePoint {
  glm::vec3 position, normal;  // normal: geometric, unit, facing the incoming ray
};

SurfacePoint surfaceAt(const Scene& scene, const HtRay& ray, const HtHit& hit) {
  const glm::uvec3 tri = scene.triangles[hit.triId];
  const glm::vec3 a = scene.positions[tri.x], b = scene.positions[tri.y], c = scene.positions[tri.z];
  const glm::vec3 p = a * (1.0f - hit.u - hit.v) + b * hit.u + c * hit.v;
  glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  if (glm::dot(n, ray.dir) > 0.0f) n = -n;
  return {p, n};
}

// Cosine-weighted direction about n (Malley's method on an orthonormal basis, Duff et al. 2017).
glm::vec3 cosineDirection(glm::vec3 n, float u1, float u2) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  const glm::vec3 t(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::vec3 s(b, sign + n.y * n.y * a, -n.y);
  const float r = std::sqrt(u1), phi = 6.2831853f * u2;
  const float z = std::sqrt(std::max(0.0f, 1.0f - u1));
  return glm::normalize(t * (r * std::cos(phi)) + s * (r * std::sin(phi)) + n * z);
}

HtRay makeRay(glm::vec3 origin, glm::vec3 dir, float tmax) {
  HtRay ray{};
  ray.origin = origin;
  ray.dir = dir;
  ray.tmin = 0.0f;
  ray.tmax = tmax;
  return ray;
}

}  // namespace

RaySet makeTiledPrimaryRays(const Bounds3& bounds, std::uint32_t size) {
  const RayBatch batch = makePinholeRays(bounds, size);
  RaySet set{"primary", RayQuery::Closest, {}};
  set.rays.reserve(batch.rays.size());
  for (std::uint32_t ty = 0; ty < size; ty += kTile) {
    for (std::uint32_t tx = 0; tx < size; tx += kTile) {
      for (std::uint32_t y = ty; y < std::min(size, ty + kTile); ++y) {
        for (std::uint32_t x = tx; x < std::min(size, tx + kTile); ++x) {
          set.rays.push_back(batch.rays[std::size_t(y) * size + x]);
        }
      }
    }
  }
  return set;
}

std::vector<RaySet> makeSecondaryRays(const Scene& scene, std::span<const HtRay> primary, std::span<const HtHit> hits,
                                      std::uint32_t seed) {
  const Bounds3 bounds = scene.bounds();
  const glm::vec3 light = bounds.hi + 0.5f * bounds.extent() * glm::vec3(0.0f, 1.0f, 1.0f);
  RaySet shadow{"shadow", RayQuery::Occluded, {}}, diffuse{"diffuse", RayQuery::Closest, {}},
      mirror{"mirror", RayQuery::Closest, {}};
  for (std::size_t i = 0; i < hits.size(); ++i) {
    if (hits[i].triId == gpu_shared::HT_MISS) continue;
    const SurfacePoint s = surfaceAt(scene, primary[i], hits[i]);
    const glm::vec3 origin = gpu_shared::ht_offset_ray(s.position, s.normal);
    // Shadow ray: unnormalised direction to the light, t in [0, 1) (ends just short of the light).
    shadow.rays.push_back(makeRay(origin, light - origin, 1.0f - 1e-4f));
    const auto index = std::uint32_t(i);
    diffuse.rays.push_back(
        makeRay(origin, cosineDirection(s.normal, hashToUnit(index, 0, seed), hashToUnit(index, 1, seed)), kFloatMax));
    const glm::vec3 d = glm::normalize(primary[i].dir);
    mirror.rays.push_back(makeRay(origin, glm::normalize(d - 2.0f * glm::dot(d, s.normal) * s.normal), kFloatMax));
  }
  return {std::move(shadow), std::move(diffuse), std::move(mirror)};
}

}  // namespace ht::bench
