// instanced_soup.h - random scenes of instanced meshes for the two-level BVH tests (CPU and GPU): object-space meshes
// placed by double matrices the way the glTF loader places nodes, random placements (rigid, scaled, mirrored) and
// rays that partly aim exactly at vertices (ties at shared edges and corners).
#pragma once
#include <cstdint>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "bvh/two_level_bvh.h"
#include "tests/bvh/bvh_test_util.h"

namespace ht::bvh::test {

using gpu_shared::HtRay;

// A soup of instances: object-space meshes placed by double matrices (as the glTF loader places nodes).
struct InstancedSoup {
  std::vector<Mesh> meshes;
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;
  std::vector<InstanceRange> ranges;
  std::vector<uint32_t> firstVertex;

  void place(uint32_t instance, const glm::dmat4& world) {
    const Mesh& mesh = meshes[static_cast<size_t>(ranges[instance].mesh)];
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    for (size_t v = 0; v < mesh.positions.size(); ++v)
      positions[firstVertex[instance] + v] = glm::vec3(world * glm::dvec4(glm::dvec3(mesh.positions[v]), 1.0));
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      glm::uvec3 tri = mesh.triangles[t] + glm::uvec3(firstVertex[instance]);
      if (mirrored) std::swap(tri.y, tri.z);
      triangles[ranges[instance].firstTriangle + t] = tri;
    }
  }
  uint32_t add(uint32_t mesh, const glm::dmat4& world) {
    const Mesh& m = meshes[mesh];
    ranges.push_back({static_cast<uint32_t>(triangles.size()), static_cast<uint32_t>(m.triangles.size()),
                      static_cast<int32_t>(mesh)});
    firstVertex.push_back(static_cast<uint32_t>(positions.size()));
    positions.resize(positions.size() + m.positions.size());
    triangles.resize(triangles.size() + m.triangles.size());
    place(static_cast<uint32_t>(ranges.size() - 1), world);
    return static_cast<uint32_t>(ranges.size() - 1);
  }
};

inline glm::dmat4 randomPlacement(std::mt19937& rng, bool allowMirror) {
  std::uniform_real_distribution<double> pos(-3.0, 3.0), angle(0.0, 6.283185307179586), scale(0.5, 1.5);
  std::uniform_int_distribution<int> coin(0, 3);
  glm::dvec3 axis = glm::dvec3(randomUnitVector(rng));
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(pos(rng), pos(rng), pos(rng)));
  m = glm::rotate(m, angle(rng), axis);
  glm::dvec3 s(scale(rng));
  if (allowMirror && coin(rng) == 0) s.x = -s.x;
  return glm::scale(m, s);
}

inline InstancedSoup randomScene(std::mt19937& rng, uint32_t instances) {
  InstancedSoup soup;
  soup.meshes.push_back(closedSphere(glm::vec3(0.0f), 0.6f, 10, 14));  // shared vertices: ties at edges
  soup.meshes.push_back(randomSoup(150, 0.3f, rng()));
  soup.meshes.push_back(closedSphere(glm::vec3(0.2f, 0.0f, 0.1f), 0.4f, 6, 9));
  std::uniform_int_distribution<uint32_t> pick(0, 2);
  for (uint32_t i = 0; i < instances; ++i) soup.add(pick(rng), randomPlacement(rng, true));
  return soup;
}

inline std::vector<HtRay> randomRays(std::mt19937& rng, const InstancedSoup& soup, uint32_t count) {
  std::uniform_real_distribution<float> box(-5.0f, 5.0f), inner(-3.5f, 3.5f);
  std::uniform_int_distribution<size_t> vertex(0, soup.positions.size() - 1);
  std::vector<HtRay> rays;
  for (uint32_t i = 0; i < count; ++i) {
    glm::vec3 origin(box(rng), box(rng), box(rng));
    // A third of the rays aim exactly at a vertex: several triangles meet there (ties and edge cases).
    glm::vec3 target = i % 3 == 0 ? soup.positions[vertex(rng)] : glm::vec3(inner(rng), inner(rng), inner(rng));
    if (target == origin) continue;
    rays.push_back(makeRay(origin, target - origin, 0.0f, i % 5 == 0 ? 0.7f : INFINITY));
  }
  return rays;
}

}  // namespace ht::bvh::test
