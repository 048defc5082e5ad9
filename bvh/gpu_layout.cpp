// gpu_layout.cpp - see gpu_layout.h. Node layout: Aila & Laine 2009 "Compact2" (docs/BVH.md §2.4, §3, gpu_node.h).
#include "bvh/gpu_layout.h"

#include <limits>
#include <string>

#include "bvh/bvh_traversal.h"
#include "common/error.h"

namespace ht::bvh {
namespace {

using gpu_shared::GpuBvhNode;

static_assert(sizeof(GpuBvhNode) == 64, "GpuBvhNode must be 64 bytes");

constexpr float kInf = std::numeric_limits<float>::infinity();

struct ChildSlot {
  glm::vec3 lo{kInf};
  glm::vec3 hi{-kInf};  // default: empty box, never entered by the slab test
  uint32_t ref = 0;
  uint32_t count = 0;
};

GpuBvhNode packNode(const ChildSlot& c0, const ChildSlot& c1) {
  GpuBvhNode n;
  n.c0xy = glm::vec4(c0.lo.x, c0.hi.x, c0.lo.y, c0.hi.y);
  n.c1xy = glm::vec4(c1.lo.x, c1.hi.x, c1.lo.y, c1.hi.y);
  n.c01z = glm::vec4(c0.lo.z, c0.hi.z, c1.lo.z, c1.hi.z);
  n.link = glm::uvec4(c0.ref, c1.ref, c0.count, c1.count);
  return n;
}

[[noreturn]] void throwLayout(const std::string& problem) { throw SceneError("<bvh layout>", problem); }

ChildSlot leafSlot(const Bvh2& bvh, const Bvh2Node& leaf) {
  if (uint64_t{leaf.leftFirst} + leaf.triCount > bvh.primIndex.size()) throwLayout("leaf range out of primIndex");
  if (leaf.triCount > gpu_shared::HT_MAX_LEAF_SIZE) {
    throwLayout("leaf of " + std::to_string(leaf.triCount) +
                " triangles exceeds HT_MAX_LEAF_SIZE (build with "
                "maxLeafSize <= 16)");
  }
  return ChildSlot{leaf.lo, leaf.hi, leaf.leftFirst, leaf.triCount};
}

std::vector<glm::vec4> packTriangles(const Bvh2& bvh, std::span<const glm::vec3> positions,
                                     std::span<const glm::uvec3> triangles) {
  std::vector<glm::vec4> out;
  out.reserve(bvh.primIndex.size() * gpu_shared::HT_TRI_STRIDE);
  for (uint32_t id : bvh.primIndex) {
    if (id >= triangles.size()) throwLayout("triangle id " + std::to_string(id) + " out of range");
    const glm::uvec3& tri = triangles[id];
    if (tri.x >= positions.size() || tri.y >= positions.size() || tri.z >= positions.size()) {
      throwLayout("triangle " + std::to_string(id) + " has a vertex index out of range");
    }
    out.emplace_back(positions[tri.x], glm::uintBitsToFloat(id));
    out.emplace_back(positions[tri.y], 0.0f);
    out.emplace_back(positions[tri.z], 0.0f);
  }
  return out;
}

// Inner Bvh2 nodes -> GpuBvhNodes; both inner children of a node get consecutive indices.
std::vector<GpuBvhNode> packInnerNodes(const Bvh2& bvh) {
  std::vector<GpuBvhNode> out(1);
  struct Pending {
    uint32_t bvhNode, gpuNode;
  };
  std::vector<Pending> stack{{0, 0}};
  while (!stack.empty()) {
    Pending p = stack.back();
    stack.pop_back();
    const Bvh2Node& parent = bvh.nodes[p.bvhNode];
    ChildSlot slots[2];
    for (uint32_t k = 0; k < 2; ++k) {
      const uint32_t childIdx = parent.leftFirst + k;
      if (childIdx >= bvh.nodes.size()) throwLayout("child index " + std::to_string(childIdx) + " out of range");
      const Bvh2Node& child = bvh.nodes[childIdx];
      if (child.isLeaf()) {
        slots[k] = leafSlot(bvh, child);
        continue;
      }
      slots[k] = ChildSlot{child.lo, child.hi, static_cast<uint32_t>(out.size()), 0};
      if (out.size() > gpu_shared::HT_REF_INDEX_MASK) throwLayout("more than 2^27 nodes");
      if (out.size() >= bvh.nodes.size()) throwLayout("malformed Bvh2 (more inner nodes than nodes)");
      out.emplace_back();
    }
    out[p.gpuNode] = packNode(slots[0], slots[1]);
    for (int k = 1; k >= 0; --k) {  // left child on top: its subtree is packed first
      if (slots[k].count == 0) stack.push_back({parent.leftFirst + k, slots[k].ref});
    }
  }
  return out;
}

}  // namespace

std::vector<GpuBvhNode> toGpuNodes(const Bvh2& bvh) {
  if (bvh.primIndex.size() > gpu_shared::HT_REF_INDEX_MASK) throwLayout("more than 2^27 triangle slots");
  if (bvh.nodes.empty()) return {packNode(ChildSlot{}, ChildSlot{})};
  if (bvh.nodes[0].isLeaf()) return {packNode(leafSlot(bvh, bvh.nodes[0]), ChildSlot{})};
  return packInnerNodes(bvh);
}

GpuBvh toGpuLayout(const Bvh2& bvh, std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles) {
  GpuBvh gpu;
  gpu.report = bvh.report;
  gpu.nodes = toGpuNodes(bvh);
  gpu.triangles = packTriangles(bvh, positions, triangles);
  return gpu;
}

GpuBvh buildGpuBvh(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                   const BuildOptions& options) {
  return toGpuLayout(buildBinnedSah(positions, triangles, options), positions, triangles);
}

void tagTriangleParts(GpuBvh& bvh, std::span<const uint32_t> partOfTriangle) {
  constexpr size_t kStride = gpu_shared::HT_TRI_STRIDE;
  for (size_t slot = 0; slot + kStride <= bvh.triangles.size(); slot += kStride) {
    const uint32_t id = glm::floatBitsToUint(bvh.triangles[slot].w);
    if (id >= partOfTriangle.size()) throwLayout("triangle id " + std::to_string(id) + " has no part");
    bvh.triangles[slot + 1].w = static_cast<float>(partOfTriangle[id]);
  }
}

}  // namespace ht::bvh
