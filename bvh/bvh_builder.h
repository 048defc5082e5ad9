// bvh_builder.h - binned SAH BVH builder producing a binary BVH in Wald's 32-byte node layout.
//
// Binned SAH after Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies" (RT 2007), with the
// parameters of docs/BVH.md §8.2: 32 centroid bins (Embree NUM_OBJECT_BINS, kernels/builders/bvh_builder_sah.h),
// C_trav = C_int = 1 (tinybvh), a hard leaf-depth bound so the GPU traversal stack (HT_BVH_MAX_DEPTH) is
// provably large enough, and subtrees built in parallel.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ht::bvh {

struct BuildOptions {
  uint32_t bins = 32;        // centroid bins per axis, 2..256
  uint32_t maxLeafSize = 4;  // 1..16 (HT_MAX_LEAF_SIZE): leaves never hold more triangles
  uint32_t maxDepth = 64;    // 1..64 (HT_BVH_MAX_DEPTH): hard bound on leaf depth (root = depth 0)
  uint32_t threads = 0;      // 0 = std::thread::hardware_concurrency()
};

struct BuildReport {
  double buildMs = 0.0;  // wall time of buildBinnedSah (validation, binning, tree, report)
  double sahCost = 0.0;  // tinybvh formula, see bvh_builder.cpp; 0 for an empty tree
  uint32_t nodeCount = 0, leafCount = 0, maxDepth = 0;  // maxDepth: deepest leaf, root = 0
  uint64_t trianglesIn = 0, trianglesDropped = 0;       // dropped: zero area, NaN/Inf, bad index
  double avgLeafSize = 0.0;
  std::string summary() const;  // one line, e.g. for logs
};

// Wald's 32-byte node (tinybvh `BVH`, docs/BVH.md §3). Inner node: triCount == 0 and children at leftFirst and
// leftFirst + 1. Leaf: triCount > 0 triangles at primIndex[leftFirst .. leftFirst + triCount).
struct Bvh2Node {
  glm::vec3 lo;
  uint32_t leftFirst;
  glm::vec3 hi;
  uint32_t triCount;
  bool isLeaf() const { return triCount > 0; }
};
static_assert(sizeof(Bvh2Node) == 32, "Bvh2Node must be 32 bytes");

// nodes[0] is the root; an empty tree (no usable triangle) has no nodes. primIndex holds original triangle
// indices in leaf order; dropped triangles do not appear.
struct Bvh2 {
  std::vector<Bvh2Node> nodes;
  std::vector<uint32_t> primIndex;
  BuildReport report;
};

// Builds the BVH of the triangle soup (positions indexed by triangles). Never throws on bad geometry (it
// is dropped and counted); throws ht::ConfigError for options outside the documented ranges, and if the
// kept triangles cannot fit under maxDepth with maxLeafSize (only possible for maxDepth < 64).
Bvh2 buildBinnedSah(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                    const BuildOptions& options);

// SAH cost of a built tree with tinybvh's formula (C_trav = C_int = 1, half-area SA):
// (1/SA(root)) * [sum over inner nodes SA(n) + sum over leaves SA(l) * count(l)].
double sahCost(const Bvh2& bvh);

}  // namespace ht::bvh
