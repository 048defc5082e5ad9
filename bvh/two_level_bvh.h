// two_level_bvh.h - a two-level BVH over the instances of a triangle soup: one bottom-level tree shape per mesh
// (instances of the same mesh share it), a top level over the instances' world boxes that is rebuilt in
// microseconds when an instance moves (docs/BVH.md §9, docs/REUSE.md §3).
//
// Bit-exactness with the flattened BVH: every instance keeps its own world-space triangles -- the very floats
// of the flattened soup -- and its own world-space node boxes, refitted over the shared tree shape. Rays are
// never transformed into object space (that would round differently from the flattened soup). Traced with
// ordered_traversal.h, hits equal the flattened BVH's hits bit for bit: same triangles, same ray, least (t, id).
// What instancing shares is the build: a moved instance is refitted (O(its triangles)), not rebuilt, and the
// top level is rebuilt over the instance boxes (O(instances log instances)).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/aabb.h"
#include "bvh/bvh_builder.h"
#include "bvh/gpu_node.h"
#include "bvh/ordered_traversal.h"

namespace ht::bvh {

// A contiguous range of the soup's triangles placed by one instance. Instances with the same mesh >= 0 and the
// same triangle count are the same mesh under different transforms (local triangle i corresponds); mesh < 0:
// geometry of its own. Ranges must not overlap; triangles outside every range are not traced.
struct InstanceRange {
  uint32_t firstTriangle = 0, triangleCount = 0;
  int32_t mesh = -1;
};

// Where instance i's bottom level lies in the concatenated buffers: nodes [nodeBase, +nodeCount) of blasNodes(),
// triangle slots [slotBase, +slotCount) (HT_TRI_STRIDE vec4 each) of blasTriangles().
struct InstanceSlots {
  uint32_t nodeBase = 0, nodeCount = 0, slotBase = 0, slotCount = 0;
};

struct TwoLevelTimings {
  double refitMs = 0.0;     // bottom levels refitted (and repacked) in the last update
  double topLevelMs = 0.0;  // top-level rebuild of the last build or update
};

class TwoLevelBvh {
 public:
  // Builds every bottom level (one tree shape per mesh, built on its first instance's world triangles) and the
  // top level. Throws ht::SceneError for ranges out of bounds or overlapping.
  TwoLevelBvh(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
              std::span<const InstanceRange> instances, const BuildOptions& options = {});

  // After the world positions (and possibly the winding) of the given instances changed in the soup: refits
  // their bottom levels over the new world triangles and rebuilds the top level.
  void updateInstances(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                       std::span<const uint32_t> moved);
  // Top level alone, over the current instance boxes (what a pure rigid move of a shared BLAS would cost).
  void rebuildTopLevel();

  gpu_shared::TwoLevelView view() const;
  const TwoLevelTimings& timings() const { return timings_; }
  size_t instanceCount() const { return instances_.size(); }
  size_t shapeCount() const { return shapes_.size(); }  // distinct bottom-level tree shapes
  const Aabb& instanceBox(uint32_t i) const { return instances_[i].box; }
  InstanceSlots instanceSlots(uint32_t i) const;
  const InstanceRange& instanceRange(uint32_t i) const { return instances_[i].range; }
  // Whether the last updateInstances laid the bottom levels out anew (a placement needed a tree shape of its own):
  // then every instance's range may have moved, not only the moved instances'.
  bool lastUpdateRelaidOut() const { return relaidOut_; }
  size_t memoryBytes() const;

  // Concatenated buffers (what a GPU kernel binds).
  const std::vector<gpu_shared::GpuBvhNode>& topNodes() const { return topNodes_; }
  const std::vector<glm::uvec4>& instanceTable() const { return instanceTable_; }
  const std::vector<gpu_shared::GpuBvhNode>& blasNodes() const { return blasNodes_; }
  const std::vector<glm::vec4>& blasTriangles() const { return blasTriangles_; }

 private:
  struct Shape {  // a bottom-level tree shape over local triangle ids
    Bvh2 tree;
    std::vector<bool> inTree;  // per local triangle
  };
  struct Instance {
    InstanceRange range;
    uint32_t shape = 0;
    uint32_t nodeBase = 0, nodeCount = 0, slotBase = 0, slotCount = 0;
    Aabb box;
  };

  uint32_t shapeFor(const InstanceRange& range, std::span<const glm::vec3> positions,
                    std::span<const glm::uvec3> triangles);
  // Refits instance i's nodes and triangle slots into the concatenated buffers; false if the sizes changed.
  bool packInstance(uint32_t i, std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles);
  void relayout(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles);

  BuildOptions options_;
  std::vector<Shape> shapes_;
  std::vector<Instance> instances_;
  std::vector<gpu_shared::GpuBvhNode> topNodes_;
  std::vector<glm::uvec4> instanceTable_;
  std::vector<gpu_shared::GpuBvhNode> blasNodes_;
  std::vector<glm::vec4> blasTriangles_;
  TwoLevelTimings timings_;
  bool relaidOut_ = false;
};

}  // namespace ht::bvh
