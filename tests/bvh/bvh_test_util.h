// bvh_test_util.h - meshes, rays and invariant checks shared by the bvh tests.
#pragma once
#include <cmath>
#include <cstdint>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "bvh/bvh_builder.h"
#include "bvh/ray_types.h"

namespace ht::bvh::test {

// Sanitizer / debug builds run fewer rays; release figures are what the brief asks to report.
#if defined(HT_SANITIZED_BUILD) || !defined(NDEBUG)
inline constexpr bool kSlowBuild = true;
#else
inline constexpr bool kSlowBuild = false;
#endif
inline constexpr uint32_t scaled(uint32_t release, uint32_t slow) { return kSlowBuild ? slow : release; }

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;
};

inline constexpr const char* kBunnyPath = "/usr/share/glmark2/models/bunny.obj";

// Minimal OBJ reader: `v x y z` and `f i j k ...` (v, v/t, v/t/n, v//n, negative indices), fan-triangulated.
inline Mesh loadObj(const std::string& path) {
  Mesh mesh;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      glm::vec3 p;
      ls >> p.x >> p.y >> p.z;
      mesh.positions.push_back(p);
    } else if (tag == "f") {
      std::vector<uint32_t> face;
      std::string token;
      while (ls >> token) {
        long idx = std::stol(token.substr(0, token.find('/')));
        face.push_back(static_cast<uint32_t>(idx < 0 ? static_cast<long>(mesh.positions.size()) + idx : idx - 1));
      }
      for (size_t k = 2; k < face.size(); ++k) mesh.triangles.emplace_back(face[0], face[k - 1], face[k]);
    }
  }
  return mesh;
}

// n random triangles in [0,1]^3 with edge lengths up to `size`.
inline Mesh randomSoup(uint32_t n, float size, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), offset(-size, size);
  Mesh mesh;
  for (uint32_t i = 0; i < n; ++i) {
    glm::vec3 a(unit(rng), unit(rng), unit(rng));
    glm::vec3 b = a + glm::vec3(offset(rng), offset(rng), offset(rng));
    glm::vec3 c = a + glm::vec3(offset(rng), offset(rng), offset(rng));
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.triangles.emplace_back(base, base + 1, base + 2);
  }
  return mesh;
}

// Closed UV sphere (shared vertices, poles included): every ray from inside must hit it.
inline Mesh closedSphere(glm::vec3 center, float radius, uint32_t rings, uint32_t segments) {
  Mesh mesh;
  mesh.positions.push_back(center + glm::vec3(0, 0, radius));
  for (uint32_t r = 1; r < rings; ++r) {
    double theta = std::numbers::pi * r / rings;
    for (uint32_t s = 0; s < segments; ++s) {
      double phi = 2.0 * std::numbers::pi * s / segments;
      glm::dvec3 p(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      mesh.positions.push_back(glm::vec3(glm::dvec3(center) + p * double(radius)));
    }
  }
  const uint32_t south = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.push_back(center - glm::vec3(0, 0, radius));
  auto ring = [&](uint32_t r, uint32_t s) { return 1 + (r - 1) * segments + s % segments; };
  for (uint32_t s = 0; s < segments; ++s) mesh.triangles.emplace_back(0, ring(1, s), ring(1, s + 1));
  for (uint32_t r = 1; r + 1 < rings; ++r) {
    for (uint32_t s = 0; s < segments; ++s) {
      mesh.triangles.emplace_back(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
      mesh.triangles.emplace_back(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    }
  }
  for (uint32_t s = 0; s < segments; ++s)
    mesh.triangles.emplace_back(south, ring(rings - 1, s + 1), ring(rings - 1, s));
  return mesh;
}

inline gpu_shared::HtRay makeRay(glm::vec3 origin, glm::vec3 dir, float tmin = 0.0f, float tmax = INFINITY) {
  gpu_shared::HtRay ray;
  ray.origin = origin;
  ray.tmin = tmin;
  ray.dir = dir;
  ray.tmax = tmax;
  return ray;
}

inline glm::vec3 randomUnitVector(std::mt19937& rng) {
  std::normal_distribution<float> normal;
  glm::vec3 v;
  do { v = glm::vec3(normal(rng), normal(rng), normal(rng)); } while (glm::dot(v, v) < 1e-6f);
  return glm::normalize(v);
}

// Pinhole camera rays (width x height) looking at the mesh's bounding box from the +z side.
inline std::vector<gpu_shared::HtRay> pinholeRays(const Mesh& mesh, uint32_t width, uint32_t height) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 center = (lo + hi) * 0.5f;
  const float radius = glm::length(hi - lo) * 0.5f;
  const glm::vec3 eye = center + glm::vec3(0.1f * radius, 0.15f * radius, 2.2f * radius);
  const glm::vec3 forward = glm::normalize(center - eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  const float halfExtent = std::tan(glm::radians(30.0f) * 0.5f);
  std::vector<gpu_shared::HtRay> rays;
  rays.reserve(size_t{width} * height);
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      float sx = ((x + 0.5f) / width * 2.0f - 1.0f) * halfExtent;
      float sy = (1.0f - (y + 0.5f) / height * 2.0f) * halfExtent;
      rays.push_back(makeRay(eye, glm::normalize(forward + sx * right + sy * up)));
    }
  }
  return rays;
}

// Structural checks of a built Bvh2: a tree over all nodes; leaves partition primIndex; primIndex is exactly
// the usable triangles, each once; child boxes inside parents; leaf boxes contain their triangles; bounds on
// depth and leaf size.
inline void expectValidBvh(const Bvh2& bvh, const Mesh& mesh, const BuildOptions& options, uint64_t expectedKept) {
  ASSERT_EQ(bvh.primIndex.size(), expectedKept);
  ASSERT_EQ(bvh.report.trianglesIn, mesh.triangles.size());
  ASSERT_EQ(bvh.report.trianglesDropped, mesh.triangles.size() - expectedKept);
  std::vector<uint8_t> seenTri(mesh.triangles.size(), 0);
  for (uint32_t id : bvh.primIndex) {
    ASSERT_LT(id, mesh.triangles.size());
    ASSERT_EQ(seenTri[id]++, 0) << "triangle " << id << " referenced twice";
  }
  if (expectedKept == 0) {
    EXPECT_TRUE(bvh.nodes.empty());
    return;
  }
  std::vector<uint8_t> visited(bvh.nodes.size(), 0);
  std::vector<uint8_t> slotCovered(bvh.primIndex.size(), 0);
  struct Entry {
    uint32_t node, depth;
  };
  std::vector<Entry> stack{{0, 0}};
  uint32_t maxDepth = 0, leaves = 0;
  while (!stack.empty()) {
    Entry e = stack.back();
    stack.pop_back();
    ASSERT_LT(e.node, bvh.nodes.size());
    ASSERT_EQ(visited[e.node]++, 0) << "node " << e.node << " reached twice";
    const Bvh2Node& n = bvh.nodes[e.node];
    ASSERT_TRUE(n.lo.x <= n.hi.x && n.lo.y <= n.hi.y && n.lo.z <= n.hi.z);
    if (n.isLeaf()) {
      ++leaves;
      maxDepth = std::max(maxDepth, e.depth);
      ASSERT_LE(n.triCount, options.maxLeafSize);
      ASSERT_LE(uint64_t{n.leftFirst} + n.triCount, bvh.primIndex.size());
      for (uint32_t k = n.leftFirst; k < n.leftFirst + n.triCount; ++k) {
        ASSERT_EQ(slotCovered[k]++, 0);
        const glm::uvec3& tri = mesh.triangles[bvh.primIndex[k]];
        for (int v = 0; v < 3; ++v) {
          const glm::vec3& p = mesh.positions[tri[v]];
          ASSERT_TRUE(glm::all(glm::lessThanEqual(n.lo, p)) && glm::all(glm::lessThanEqual(p, n.hi)))
              << "leaf " << e.node << " does not contain triangle " << bvh.primIndex[k];
        }
      }
    } else {
      for (uint32_t c = n.leftFirst; c < n.leftFirst + 2; ++c) {
        ASSERT_LT(c, bvh.nodes.size());
        const Bvh2Node& child = bvh.nodes[c];
        ASSERT_TRUE(glm::all(glm::lessThanEqual(n.lo, child.lo)) && glm::all(glm::lessThanEqual(child.hi, n.hi)))
            << "child " << c << " leaves parent " << e.node;
        stack.push_back({c, e.depth + 1});
      }
    }
  }
  for (size_t i = 0; i < visited.size(); ++i) ASSERT_EQ(visited[i], 1) << "node " << i << " unreachable";
  for (size_t k = 0; k < slotCovered.size(); ++k) ASSERT_EQ(slotCovered[k], 1) << "slot " << k;
  EXPECT_LE(maxDepth, options.maxDepth);
  EXPECT_EQ(bvh.report.maxDepth, maxDepth);
  EXPECT_EQ(bvh.report.leafCount, leaves);
  EXPECT_EQ(bvh.report.nodeCount, bvh.nodes.size());
  EXPECT_EQ(bvh.nodes.size(), 2 * size_t{leaves} - 1);
}

}  // namespace ht::bvh::test
