// scene_edits.cpp - see scene_edits.h.
#include "scene/scene_edits.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "common/error.h"

namespace ht {
namespace {

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool isFinite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

}  // namespace

std::optional<std::size_t> findNode(const Scene& scene, std::string_view name) {
  for (std::size_t i = 0; i < scene.nodes.size(); ++i)
    if (scene.nodes[i].name == name) return i;
  return std::nullopt;
}

// |det(M)| / (|m0| |m1| |m2|) below this is a flattened matrix, whatever its scale.
constexpr double kMinMatrixConditioning = 1e-9;

void setNodeWorldMatrix(Scene& scene, std::string_view name, const glm::dmat4& world) {
  const std::optional<std::size_t> index = findNode(scene, name);
  if (!index) {
    std::string names;
    for (const SceneNode& n : scene.nodes) names += (names.empty() ? "" : ", ") + n.name;
    throw SceneError(scene.name,
                     "no node named '" + std::string(name) + "' (nodes: " + (names.empty() ? "none" : names) + ")");
  }
  if (!isFinite(world))
    throw SceneError(scene.name, "node '" + std::string(name) + "': the matrix has non-finite entries");
  // Scale-relative: |det| over the product of the column lengths is 1 for any rotation x scale (a node scaled by
  // 1e-4 has det 1e-12 but is fine) and 0 when the columns are dependent (flattened).
  const glm::dmat3 linear(world);
  const double det = glm::determinant(linear);
  const double scale = glm::length(linear[0]) * glm::length(linear[1]) * glm::length(linear[2]);
  if (!(scale > 0.0) || !(std::fabs(det) > kMinMatrixConditioning * scale)) {
    throw SceneError(scene.name, "node '" + std::string(name) + "': the matrix's 3x3 part is singular (determinant " +
                                     std::to_string(det) + " for column lengths multiplying to " +
                                     std::to_string(scale) + "); a node can be scaled but not flattened");
  }
  SceneNode& node = scene.nodes[*index];
  const glm::dmat4 delta = world * glm::inverse(node.world);
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(delta)));
  for (std::uint32_t v = node.firstVertex; v < node.firstVertex + node.vertexCount; ++v) {
    scene.positions[v] = glm::vec3(delta * glm::dvec4(glm::dvec3(scene.positions[v]), 1.0));
    if (v < scene.normals.size()) {
      const glm::dvec3 n = normalMatrix * glm::dvec3(scene.normals[v]);
      const double len = glm::length(n);
      if (len > 0.0) scene.normals[v] = glm::vec3(n / len);
    }
  }
  if (glm::determinant(glm::dmat3(delta)) < 0.0) {
    for (std::uint32_t t = node.firstTriangle; t < node.firstTriangle + node.triangleCount; ++t)
      std::swap(scene.triangles[t].y, scene.triangles[t].z);
  }
  node.world = world;
}

Bounds3 nodeWorldBounds(const Scene& scene, std::size_t index) {
  Bounds3 b;
  const SceneNode& node = scene.nodes.at(index);
  for (std::uint32_t v = node.firstVertex; v < node.firstVertex + node.vertexCount; ++v) b.extend(scene.positions[v]);
  return b;
}

glm::vec4 nodeWorldBall(const Scene& scene, std::size_t index) {
  const Bounds3 b = nodeWorldBounds(scene, index);
  if (b.empty()) return kNoBall;
  const glm::dvec3 c = 0.5 * (glm::dvec3(b.lo) + glm::dvec3(b.hi));
  const SceneNode& node = scene.nodes.at(index);
  double r2 = 0.0;
  for (std::uint32_t v = node.firstVertex; v < node.firstVertex + node.vertexCount; ++v) {
    const glm::dvec3 d = glm::dvec3(scene.positions[v]) - c;
    r2 = std::max(r2, glm::dot(d, d));
  }
  const glm::dvec3 extent = glm::dvec3(b.hi) - glm::dvec3(b.lo);
  const double slack =
      1e-6 * (std::max({extent.x, extent.y, extent.z}) + std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}));
  return glm::vec4(glm::vec3(c), static_cast<float>(std::sqrt(r2) * (1.0 + 1e-6) + slack));
}

void editLight(Scene& scene, std::size_t index, const LightEdit& edit) {
  const std::string what = "light " + std::to_string(index);
  if (index >= scene.lights.size()) {
    throw SceneError(scene.name,
                     what + " does not exist (the scene has " + std::to_string(scene.lights.size()) + " light(s))");
  }
  if ((edit.position && !isFinite(*edit.position)) || (edit.direction && !isFinite(*edit.direction)) ||
      (edit.color && !isFinite(*edit.color)) || (edit.intensity && !std::isfinite(*edit.intensity)))
    throw SceneError(scene.name, what + ": values must be finite");
  if (edit.direction && !(glm::length(*edit.direction) > 0.0))
    throw SceneError(scene.name, what + ": direction must be non-zero");
  if (edit.color && (edit.color->x < 0.0 || edit.color->y < 0.0 || edit.color->z < 0.0))
    throw SceneError(scene.name, what + ": color must be >= 0 (linear RGB)");
  if (edit.intensity && *edit.intensity < 0.0) throw SceneError(scene.name, what + ": intensity must be >= 0");
  Light& light = scene.lights[index];
  if (edit.position) light.position = glm::vec3(*edit.position);
  if (edit.direction) light.direction = glm::vec3(glm::normalize(*edit.direction));
  if (edit.color) light.color = glm::vec3(*edit.color);
  if (edit.intensity) light.intensity = static_cast<float>(*edit.intensity);
}

}  // namespace ht
