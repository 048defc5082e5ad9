// gpu_layout.h - conversion of a Bvh2 into the buffers the GPU kernel traverses (gpu_node.h layout).
#pragma once
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh_builder.h"
#include "bvh/gpu_node.h"

namespace ht::bvh {

struct GpuBvh {
  std::vector<gpu_shared::GpuBvhNode> nodes;  // nodes[0] = root; never empty
  std::vector<glm::vec4> triangles;           // HT_TRI_STRIDE vec4 per slot, leaf order; v0.w = triangle id bits
  BuildReport report;
};

// One GpuBvhNode per inner Bvh2 node (depth-first order, root first). A Bvh2 whose root is a leaf becomes a
// root with that leaf as child 0 and an empty child 1; an empty Bvh2 becomes a root with two empty children
// (empty box: lo = +inf, hi = -inf; link 0). Triangle slot i holds triangle bvh.primIndex[i].
// Throws ht::SceneError if a triangle index is out of range of `positions`/`triangles` (bvh not built from
// them), or the tree exceeds the packed-reference limits of bvh_traversal.h (2^27 nodes or slots).
GpuBvh toGpuLayout(const Bvh2& bvh, std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles);

// The node part of toGpuLayout alone (leaf references index bvh.primIndex): the top level of a two-level BVH.
std::vector<gpu_shared::GpuBvhNode> toGpuNodes(const Bvh2& bvh);

// Writes each slot's convex part (bvh/gpu_node.h: vertex 1's .w, a float value) from partOfTriangle[triangle id]
// (0 = none; below 2^24), for ht_trace_any_leaving. Throws ht::SceneError if a slot's id is out of its range.
void tagTriangleParts(GpuBvh& bvh, std::span<const uint32_t> partOfTriangle);

// buildBinnedSah + toGpuLayout.
GpuBvh buildGpuBvh(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                   const BuildOptions& options);

}  // namespace ht::bvh
