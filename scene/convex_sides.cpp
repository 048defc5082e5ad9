// convex_sides.cpp - see convex_sides.h.
#include "scene/convex_sides.h"

#include <algorithm>
#include <vector>

#include <glm/glm.hpp>

namespace ht {

std::uint8_t convexSides(const Scene& scene, const SceneNode& node, std::uint64_t* planeTests) {
  const std::uint64_t first = node.firstTriangle, end = first + node.triangleCount;
  const std::uint64_t v0 = node.firstVertex, v1 = v0 + node.vertexCount;
  if (node.triangleCount == 0 || end > scene.triangles.size() || v1 > scene.positions.size()) return 0;
  if (std::uint64_t{node.triangleCount} * node.vertexCount > kMaxConvexPlaneTests) return 0;
  for (std::uint64_t t = first; t < end; ++t) {
    const glm::uvec3 tri = scene.triangles[t];
    for (int c = 0; c < 3; ++c)
      if (tri[c] < v0 || tri[c] >= v1) return 0;  // shares vertices with something else: not the node's own surface
  }
  // The vertices as doubles, one array per axis (the loop below vectorises over them).
  std::vector<double> xs, ys, zs;
  xs.reserve(node.vertexCount), ys.reserve(node.vertexCount), zs.reserve(node.vertexCount);
  glm::dvec3 lo(1e300), hi(-1e300);
  for (std::uint64_t v = v0; v < v1; ++v) {
    const glm::dvec3 p(scene.positions[v]);
    xs.push_back(p.x), ys.push_back(p.y), zs.push_back(p.z);
    lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  const double tolerance = kConvexPlaneTolerance * glm::length(hi - lo);
  if (!(tolerance >= 0.0)) return 0;  // non-finite positions
  std::uint8_t sides = kConvexFront | kConvexBack;
  for (std::uint64_t t = first; t < end && sides != 0; ++t) {
    const glm::uvec3 tri = scene.triangles[t];
    const glm::dvec3 p0(scene.positions[tri.x]), p1(scene.positions[tri.y]), p2(scene.positions[tri.z]);
    const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
    const double len = glm::length(n);
    if (!(len > 0.0)) continue;  // a degenerate triangle has no plane (and no ray meets it)
    const glm::dvec3 u = n / len;
    const double offset = glm::dot(u, p0);
    double most = -1e300, least = 1e300;
    for (std::size_t k = 0; k < xs.size(); ++k) {
      const double d = u.x * xs[k] + u.y * ys[k] + u.z * zs[k] - offset;
      most = std::max(most, d);
      least = std::min(least, d);
    }
    if (planeTests) *planeTests += xs.size();
    if (most > tolerance) sides &= static_cast<std::uint8_t>(~kConvexFront);
    if (least < -tolerance) sides &= static_cast<std::uint8_t>(~kConvexBack);
  }
  return sides;
}

namespace {

// For a node whose mesh was found convex on another node (an affine image of it): which side is outside here, from
// the side of the first triangle's plane the vertices' centroid lies on (a mirroring matrix may have kept the
// winding). 0 where that cannot tell (a flat node is handled by the caller).
std::uint8_t outsideOfAffineImage(const Scene& scene, const SceneNode& node) {
  glm::dvec3 centroid(0.0);
  for (std::uint32_t v = node.firstVertex; v < node.firstVertex + node.vertexCount; ++v)
    centroid += glm::dvec3(scene.positions[v]);
  centroid /= static_cast<double>(node.vertexCount);
  for (std::uint32_t t = node.firstTriangle; t < node.firstTriangle + node.triangleCount; ++t) {
    const glm::uvec3 tri = scene.triangles[t];
    const glm::dvec3 p0(scene.positions[tri.x]), p1(scene.positions[tri.y]), p2(scene.positions[tri.z]);
    const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
    const double len = glm::length(n);
    if (!(len > 0.0)) continue;
    const double d = glm::dot(n / len, centroid - p0);
    if (d != 0.0) return d < 0.0 ? kConvexFront : kConvexBack;
  }
  return 0;
}

}  // namespace

std::size_t markConvexNodes(Scene& scene) {
  std::vector<std::uint8_t> meshSides;  // by glTF mesh: 0xFF = not checked yet
  std::uint64_t spent = 0;
  std::size_t unmarked = 0;
  // The node's test within the budget, or 0 (not marked) where its worst case would overrun it.
  const auto test = [&](const SceneNode& node) -> std::uint8_t {
    if (std::uint64_t{node.triangleCount} * node.vertexCount > kMaxConvexPlaneTestsPerScene - spent) {
      unmarked += std::uint64_t{node.triangleCount} * node.vertexCount <= kMaxConvexPlaneTests;
      return 0;
    }
    return convexSides(scene, node, &spent);
  };
  for (SceneNode& node : scene.nodes) {
    const bool shared = node.mesh >= 0 && node.vertexCount > 0;
    const std::size_t mesh = shared ? static_cast<std::size_t>(node.mesh) : 0;
    if (shared && mesh >= meshSides.size()) meshSides.resize(mesh + 1, 0xFF);
    if (!shared || meshSides[mesh] == 0xFF) {
      node.convexSides = test(node);
      if (shared) meshSides[mesh] = node.convexSides;
      continue;
    }
    // Nodes of one mesh are affine images of each other (glTF node matrices), and an affine map keeps a convex
    // mesh convex: only the outside may have turned, where a mirroring matrix kept the winding.
    const std::uint8_t sides = meshSides[mesh];
    const bool oneSide = sides == kConvexFront || sides == kConvexBack;
    node.convexSides = oneSide ? outsideOfAffineImage(scene, node) : test(node);
  }
  return unmarked;
}

}  // namespace ht
