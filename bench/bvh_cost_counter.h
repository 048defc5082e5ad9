// bvh_cost_counter.h - the traversal cost a tree yields on given rays, counted by a plain CPU closest-hit
// traversal of a bvh::Bvh2 (nearer child first, both child boxes tested per inner node, watertight triangle test
// of bvh/watertight_triangle.h). The same code runs on every tree, so the counts compare trees, not tracers.
#pragma once
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "bvh/bvh_builder.h"
#include "bvh/ray_types.h"

namespace ht::bench {

struct TraversalCost {
  std::uint64_t rays = 0;
  std::uint64_t nodeVisits = 0;     // inner nodes whose two child boxes were tested
  std::uint64_t triangleTests = 0;  // ray-triangle tests
  std::uint64_t hits = 0;
  // Loop iterations (one inner node or one leaf each), and the same in lockstep groups of 8 consecutive rays: a group
  // of SIMD lanes runs as long as its longest ray (lavapipe's 8-wide invocations), 8 x max(iterations) per group.
  std::uint64_t steps = 0;
  std::uint64_t lockstep8 = 0;
  double laneEfficiency() const { return lockstep8 ? double(steps) / double(lockstep8) : 0.0; }
  double nodesPerRay() const { return rays ? double(nodeVisits) / double(rays) : 0.0; }
  double trianglesPerRay() const { return rays ? double(triangleTests) / double(rays) : 0.0; }
  // C_trav * nodes + C_int * triangles per ray, C_trav = C_int = 1 (the SAH cost's units).
  double costPerRay() const { return nodesPerRay() + trianglesPerRay(); }
};

// Closest-hit (anyHit = false) or first-hit (true) traversal of every ray; threads = 0 -> all cores.
TraversalCost countTraversalCost(const bvh::Bvh2& tree, std::span<const glm::vec3> positions,
                                 std::span<const glm::uvec3> triangles, std::span<const gpu_shared::HtRay> rays,
                                 bool anyHit, unsigned threads);

}  // namespace ht::bench
