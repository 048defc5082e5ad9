// two_level_bvh.cpp - see two_level_bvh.h.
#include "bvh/two_level_bvh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "bvh/build_primitives.h"
#include "bvh/gpu_layout.h"
#include "common/error.h"

namespace ht::bvh {
namespace {

using gpu_shared::GpuBvhNode;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void checkRanges(std::span<const InstanceRange> instances, size_t triangleCount) {
  uint64_t previousEnd = 0;
  std::vector<InstanceRange> sorted(instances.begin(), instances.end());
  std::sort(sorted.begin(), sorted.end(),
            [](const InstanceRange& a, const InstanceRange& b) { return a.firstTriangle < b.firstTriangle; });
  for (const InstanceRange& r : sorted) {
    const uint64_t end = uint64_t{r.firstTriangle} + r.triangleCount;
    if (end > triangleCount || r.firstTriangle < previousEnd) {
      throw SceneError("<two-level bvh>", "instance range [" + std::to_string(r.firstTriangle) + ", " +
                                              std::to_string(end) + ") overlaps another or exceeds the " +
                                              std::to_string(triangleCount) + " triangles");
    }
    previousEnd = end;
  }
}

std::span<const glm::uvec3> localTriangles(const InstanceRange& r, std::span<const glm::uvec3> triangles) {
  return triangles.subspan(r.firstTriangle, r.triangleCount);
}

std::vector<bool> usableTriangles(std::span<const glm::vec3> positions, std::span<const glm::uvec3> local) {
  std::vector<bool> usable(local.size());
  for (size_t i = 0; i < local.size(); ++i) usable[i] = isUsableTriangle(positions, local[i]);
  return usable;
}

// Boxes of every triangle with finite corners, degenerate ones included: a rotation can make a triangle exactly
// degenerate in one placement and not in another, so a shape holds all of them and each placement masks the ones
// unusable there (packInstance). Only a triangle that is non-finite here and finite elsewhere needs another shape.
BuildPrimitives finiteTriangleBoxes(std::span<const glm::vec3> positions, std::span<const glm::uvec3> local) {
  BuildPrimitives prims;
  prims.boxes.resize(local.size());
  prims.centroids.resize(local.size());
  for (uint32_t id = 0; id < local.size(); ++id) {
    Aabb box;
    bool finite = true;
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = local[id][c];
      finite = finite && v < positions.size() && std::isfinite(positions[v].x) && std::isfinite(positions[v].y) &&
               std::isfinite(positions[v].z);
      if (finite) box.grow(positions[v]);
    }
    if (!finite) {
      ++prims.dropped;
      continue;
    }
    prims.boxes[id] = box;
    prims.centroids[id] = box.lo * 0.5f + box.hi * 0.5f;
    prims.kept.push_back(id);
  }
  return prims;
}

bool covers(const std::vector<bool>& inTree, const std::vector<bool>& usable) {
  if (inTree.size() != usable.size()) return false;
  for (size_t i = 0; i < usable.size(); ++i)
    if (usable[i] && !inTree[i]) return false;
  return true;
}

// The shape's nodes with boxes recomputed over the instance's usable world triangles (children follow their
// parent in Bvh2 order, so one reverse pass is bottom-up).
std::vector<Bvh2Node> refitNodes(const Bvh2& shape, std::span<const glm::vec3> positions,
                                 std::span<const glm::uvec3> local, const std::vector<bool>& usable) {
  std::vector<Bvh2Node> nodes = shape.nodes;
  for (size_t n = nodes.size(); n-- > 0;) {
    Bvh2Node& node = nodes[n];
    Aabb box;
    if (node.isLeaf()) {
      for (uint32_t k = node.leftFirst; k < node.leftFirst + node.triCount; ++k) {
        const uint32_t id = shape.primIndex[k];
        if (!usable[id]) continue;
        for (int c = 0; c < 3; ++c) box.grow(positions[local[id][c]]);
      }
    } else {
      box.grow(Aabb{nodes[node.leftFirst].lo, nodes[node.leftFirst].hi});
      box.grow(Aabb{nodes[node.leftFirst + 1].lo, nodes[node.leftFirst + 1].hi});
    }
    node.lo = box.lo;
    node.hi = box.hi;
  }
  return nodes;
}

}  // namespace

TwoLevelBvh::TwoLevelBvh(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                         std::span<const InstanceRange> instances, const BuildOptions& options)
    : options_(options) {
  checkRanges(instances, triangles.size());
  instances_.reserve(instances.size());
  for (const InstanceRange& range : instances) {
    Instance inst;
    inst.range = range;
    inst.shape = shapeFor(range, positions, triangles);
    instances_.push_back(inst);
  }
  relayout(positions, triangles);
  rebuildTopLevel();
}

uint32_t TwoLevelBvh::shapeFor(const InstanceRange& range, std::span<const glm::vec3> positions,
                               std::span<const glm::uvec3> triangles) {
  const std::span<const glm::uvec3> local = localTriangles(range, triangles);
  const std::vector<bool> usable = usableTriangles(positions, local);
  if (range.mesh >= 0) {
    for (const Instance& other : instances_) {
      if (other.range.mesh == range.mesh && covers(shapes_[other.shape].inTree, usable)) return other.shape;
    }
  }
  Shape shape;
  shape.tree = buildBinnedSahOverBoxes(finiteTriangleBoxes(positions, local), local.size(), options_);
  shape.inTree.assign(local.size(), false);
  for (uint32_t id : shape.tree.primIndex) shape.inTree[id] = true;
  shapes_.push_back(std::move(shape));
  return static_cast<uint32_t>(shapes_.size() - 1);
}

bool TwoLevelBvh::packInstance(uint32_t i, std::span<const glm::vec3> positions,
                               std::span<const glm::uvec3> triangles) {
  Instance& inst = instances_[i];
  const std::span<const glm::uvec3> local = localTriangles(inst.range, triangles);
  const std::vector<bool> usable = usableTriangles(positions, local);
  if (!covers(shapes_[inst.shape].inTree, usable)) inst.shape = shapeFor(inst.range, positions, triangles);
  const Shape& shape = shapes_[inst.shape];

  Bvh2 refitted;
  refitted.nodes = refitNodes(shape.tree, positions, local, usable);
  refitted.primIndex = shape.tree.primIndex;
  const std::vector<GpuBvhNode> nodes = toGpuNodes(refitted);
  const auto slots = static_cast<uint32_t>(shape.tree.primIndex.size());
  if (nodes.size() != inst.nodeCount || slots != inst.slotCount) {
    inst.nodeCount = static_cast<uint32_t>(nodes.size());
    inst.slotCount = slots;
    return false;
  }
  std::copy(nodes.begin(), nodes.end(), blasNodes_.begin() + inst.nodeBase);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  glm::vec4* out = blasTriangles_.data() + size_t{inst.slotBase} * gpu_shared::HT_TRI_STRIDE;
  for (uint32_t k = 0; k < slots; ++k) {
    const uint32_t id = shape.tree.primIndex[k];
    const float idBits = glm::uintBitsToFloat(inst.range.firstTriangle + id);
    for (int c = 0; c < 3; ++c) {
      // An unusable triangle (degenerate or non-finite in this placement) gets NaN corners: never hit.
      const glm::vec3 p = usable[id] ? positions[local[id][c]] : glm::vec3(nan);
      *out++ = glm::vec4(p, c == 0 ? idBits : 0.0f);
    }
  }
  inst.box = refitted.nodes.empty() ? Aabb{} : Aabb{refitted.nodes[0].lo, refitted.nodes[0].hi};
  return true;
}

void TwoLevelBvh::relayout(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles) {
  // First pass learns the sizes (packInstance returns false and records them), second pass packs.
  for (int pass = 0; pass < 2; ++pass) {
    uint32_t nodeBase = 0, slotBase = 0;
    for (Instance& inst : instances_) {
      inst.nodeBase = nodeBase;
      inst.slotBase = slotBase;
      nodeBase += inst.nodeCount;
      slotBase += inst.slotCount;
    }
    blasNodes_.resize(nodeBase);
    blasTriangles_.resize(size_t{slotBase} * gpu_shared::HT_TRI_STRIDE);
    bool allPacked = true;
    for (uint32_t i = 0; i < instances_.size(); ++i) allPacked &= packInstance(i, positions, triangles);
    if (allPacked) return;
  }
  throw SceneError("<two-level bvh>", "instance sizes changed while packing (internal error)");
}

void TwoLevelBvh::updateInstances(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                  std::span<const uint32_t> moved) {
  const auto start = Clock::now();
  bool sizesKept = true;
  for (uint32_t i : moved) {
    if (i >= instances_.size()) throw SceneError("<two-level bvh>", "no instance " + std::to_string(i));
    sizesKept &= packInstance(i, positions, triangles);
  }
  relaidOut_ = !sizesKept;
  if (!sizesKept) relayout(positions, triangles);  // a placement needed a tree shape of its own
  timings_.refitMs = msSince(start);
  rebuildTopLevel();
}

void TwoLevelBvh::rebuildTopLevel() {
  const auto start = Clock::now();
  BuildPrimitives prims;
  prims.boxes.resize(instances_.size());
  prims.centroids.resize(instances_.size());
  for (uint32_t i = 0; i < instances_.size(); ++i) {
    const Aabb& box = instances_[i].box;
    if (box.empty()) continue;  // nothing to hit in this instance
    prims.boxes[i] = box;
    prims.centroids[i] = box.lo * 0.5f + box.hi * 0.5f;
    prims.kept.push_back(i);
  }
  prims.dropped = instances_.size() - prims.kept.size();
  BuildOptions topOptions = options_;
  topOptions.maxLeafSize = 1;  // one instance per leaf: its box is tested before its tree is entered
  topOptions.threads = 1;      // a few thousand boxes at most: threads would cost more than they save
  const Bvh2 top = buildBinnedSahOverBoxes(std::move(prims), instances_.size(), topOptions);
  topNodes_ = toGpuNodes(top);
  instanceTable_.resize(top.primIndex.size());
  for (size_t j = 0; j < top.primIndex.size(); ++j) {
    const Instance& inst = instances_[top.primIndex[j]];
    instanceTable_[j] = glm::uvec4(inst.nodeBase, inst.slotBase, top.primIndex[j], 0u);
  }
  timings_.topLevelMs = msSince(start);
}

InstanceSlots TwoLevelBvh::instanceSlots(uint32_t i) const {
  const Instance& inst = instances_.at(i);
  return InstanceSlots{inst.nodeBase, inst.nodeCount, inst.slotBase, inst.slotCount};
}

gpu_shared::TwoLevelView TwoLevelBvh::view() const {
  return gpu_shared::TwoLevelView{topNodes_.data(), instanceTable_.data(),
                                  gpu_shared::BvhView{blasNodes_.data(), blasTriangles_.data()}};
}

size_t TwoLevelBvh::memoryBytes() const {
  size_t bytes = topNodes_.size() * sizeof(GpuBvhNode) + instanceTable_.size() * sizeof(glm::uvec4) +
                 blasNodes_.size() * sizeof(GpuBvhNode) + blasTriangles_.size() * sizeof(glm::vec4);
  for (const Shape& s : shapes_) bytes += s.tree.nodes.size() * sizeof(Bvh2Node) + s.tree.primIndex.size() * 4;
  return bytes;
}

}  // namespace ht::bvh
