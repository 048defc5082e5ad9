#include "test_meshes.h"

#include <cmath>
#include <filesystem>
#include <numbers>

#include "scene/mesh_generators.h"

namespace ht::accuracy {

TestMesh icosphere(int subdivisions) {
  Scene scene;
  makeIcosphere(scene, glm::vec3(0.0f), 1.0f, subdivisions, 0);
  TestMesh mesh;
  mesh.name = "icosphere-s" + std::to_string(subdivisions);
  mesh.positions = std::move(scene.positions);
  mesh.triangles = std::move(scene.triangles);
  mesh.interior = Interior{Interior::Kind::Ball, 0.5f, 0.0f};
  return mesh;
}

TestMesh torus(int ringSegments, int tubeSegments) {
  constexpr double kRing = 1.0, kTube = 0.4;
  TestMesh mesh;
  mesh.name = "torus-" + std::to_string(ringSegments) + "x" + std::to_string(tubeSegments);
  const auto ring = static_cast<uint32_t>(ringSegments), tube = static_cast<uint32_t>(tubeSegments);
  for (uint32_t i = 0; i < ring; ++i) {
    const double a = 2.0 * std::numbers::pi * i / ring;
    for (uint32_t j = 0; j < tube; ++j) {
      const double b = 2.0 * std::numbers::pi * j / tube;
      const double r = kRing + kTube * std::cos(b);
      mesh.positions.emplace_back(r * std::cos(a), kTube * std::sin(b), r * std::sin(a));
    }
  }
  // Indices wrap around in both directions, so the seam shares its vertices: the mesh is closed.
  auto at = [&](uint32_t i, uint32_t j) { return (i % ring) * tube + (j % tube); };
  for (uint32_t i = 0; i < ring; ++i) {
    for (uint32_t j = 0; j < tube; ++j) {
      mesh.triangles.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j + 1));
      mesh.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i + 1, j));
    }
  }
  mesh.interior = Interior{Interior::Kind::Tube, static_cast<float>(kTube / 2), static_cast<float>(kRing)};
  return mesh;
}

TestMesh bunny() {
  TestMesh mesh;
  mesh.name = "bunny";
  mesh.closed = false;
  const std::string path = "/usr/share/glmark2/models/bunny.obj";
  if (!std::filesystem::exists(path)) return mesh;
  Scene scene = loadScene(path);
  mesh.positions = std::move(scene.positions);
  mesh.triangles = std::move(scene.triangles);
  return mesh;
}

TestMesh placed(const TestMesh& mesh, float scale, glm::vec3 offset) {
  TestMesh out = mesh;
  out.scale = scale;
  out.offset = offset;
  for (glm::vec3& p : out.positions) p = glm::vec3(glm::dvec3(p) * double(scale) + glm::dvec3(offset));
  return out;
}

Scene toScene(const TestMesh& mesh) {
  Scene scene;
  scene.name = "accuracy:" + mesh.name;
  scene.positions = mesh.positions;
  scene.triangles = mesh.triangles;
  scene.materials.push_back(Material{});
  scene.triangleMaterial.assign(mesh.triangles.size(), 0u);
  return scene;
}

std::vector<TestMesh> closedMeshes() {
  return {icosphere(1), icosphere(3), icosphere(5), torus(12, 8), torus(48, 24), torus(192, 96)};
}

std::vector<Placement> placements() {
  return {
      {"origin", 1.0f, glm::vec3(0.0f)},
      {"t=1e3", 1.0f, glm::vec3(1e3f)},
      {"t=1e5", 1.0f, glm::vec3(1e5f)},
      {"t=1e6", 1.0f, glm::vec3(1e6f)},
      {"embree-verify", 2.0f, glm::vec3(148376.0f, 1234.0f, -223423.0f)},
      {"s=1e-4", 1e-4f, glm::vec3(0.0f)},
      {"s=1e-2", 1e-2f, glm::vec3(0.0f)},
      {"s=1e2", 1e2f, glm::vec3(0.0f)},
      {"s=1e4", 1e4f, glm::vec3(0.0f)},
  };
}

}  // namespace ht::accuracy
