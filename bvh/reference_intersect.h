// reference_intersect.h - brute-force, double-precision oracle for tests: every triangle is tested with the
// watertight algorithm of Woop et al. (JCGT 2013) evaluated entirely in double. Independent of the shared
// float code and of any BVH.
#pragma once
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "bvh/ray_types.h"

namespace ht::bvh {

struct ReferenceHit {
  bool hit = false;
  double t = 0.0;  // ray.tmax on a miss
  uint32_t triId = gpu_shared::HT_MISS;
  double u = 0.0, v = 0.0;  // barycentrics of vertices 1 and 2
};

// Intersection of the ray with one triangle (a, b, c) in double; t must lie in [max(tmin, 0+), tmax].
ReferenceHit referenceIntersectTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                                        const gpu_shared::HtRay& ray);

// Closest hit over all triangles (triangles with out-of-range indices are skipped).
ReferenceHit referenceClosestHit(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                 const gpu_shared::HtRay& ray);

}  // namespace ht::bvh
