// build_primitives.h - validation of the input triangle soup and per-triangle boxes for the builder.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/aabb.h"

namespace ht::bvh {

// Boxes and centroids indexed by original triangle id (entries of dropped triangles are unused).
struct BuildPrimitives {
  std::vector<Aabb> boxes;
  std::vector<glm::vec3> centroids;  // box centres
  std::vector<uint32_t> kept;        // ids of the usable triangles, ascending
  uint64_t dropped = 0;
};

// True when all three indices are in range, all vertices are finite and the triangle has non-zero area
// (cross product evaluated in double, so only exactly collinear vertices count as zero area).
bool isUsableTriangle(std::span<const glm::vec3> positions, const glm::uvec3& tri);

// Throws ht::SceneError if there are 2^32 or more triangles (ids are 32-bit).
BuildPrimitives prepareBuildPrimitives(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles);

}  // namespace ht::bvh
