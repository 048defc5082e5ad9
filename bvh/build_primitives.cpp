// build_primitives.cpp - see build_primitives.h.
#include "bvh/build_primitives.h"

#include <cmath>
#include <string>

#include "common/error.h"

namespace ht::bvh {
namespace {

bool isFinite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

glm::dvec3 toDouble(const glm::vec3& p) { return glm::dvec3(p); }

}  // namespace

bool isUsableTriangle(std::span<const glm::vec3> positions, const glm::uvec3& tri) {
  const size_t n = positions.size();
  if (tri.x >= n || tri.y >= n || tri.z >= n) return false;
  const glm::vec3& a = positions[tri.x];
  const glm::vec3& b = positions[tri.y];
  const glm::vec3& c = positions[tri.z];
  if (!isFinite(a) || !isFinite(b) || !isFinite(c)) return false;
  glm::dvec3 normal = glm::cross(toDouble(b) - toDouble(a), toDouble(c) - toDouble(a));
  return normal.x != 0.0 || normal.y != 0.0 || normal.z != 0.0;
}

BuildPrimitives prepareBuildPrimitives(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles) {
  if (triangles.size() >= 0xFFFFFFFFull) {
    throw SceneError("<triangle soup>", std::to_string(triangles.size()) +
                                            " triangles exceed the 32-bit triangle id range (split the mesh)");
  }
  BuildPrimitives prims;
  prims.boxes.resize(triangles.size());
  prims.centroids.resize(triangles.size());
  prims.kept.reserve(triangles.size());
  for (uint32_t id = 0; id < triangles.size(); ++id) {
    const glm::uvec3& tri = triangles[id];
    if (!isUsableTriangle(positions, tri)) {
      ++prims.dropped;
      continue;
    }
    Aabb box;
    box.grow(positions[tri.x]);
    box.grow(positions[tri.y]);
    box.grow(positions[tri.z]);
    prims.boxes[id] = box;
    prims.centroids[id] = box.lo * 0.5f + box.hi * 0.5f;  // no overflow near FLT_MAX
    prims.kept.push_back(id);
  }
  return prims;
}

}  // namespace ht::bvh
