// binned_sah.h - the split search of the binned SAH builder (host only).
//
// Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies" (RT 2007): triangle centroids are
// mapped to `bins` equal-width bins of the node's centroid bounds along each axis; one sweep per axis over
// the bin boxes gives the SAH cost of every plane between bins,
//   cost(plane) = SA(left) * N(left) + SA(right) * N(right)     (C_int = 1, half areas)
// and the cheapest plane over the three axes wins. Embree uses 32 bins (docs/BVH.md §2.1), tinybvh 8 (§2.2).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "bvh/aabb.h"
#include "bvh/build_primitives.h"

namespace ht::bvh {

struct NodeBounds {
  Aabb box;          // union of the triangle boxes
  Aabb centroidBox;  // bounds of the triangle centroids
};

NodeBounds computeNodeBounds(const BuildPrimitives& prims, std::span<const uint32_t> ids);

struct SahSplit {
  int axis = -1;           // -1: no split found (all centroids equal for the binned search)
  bool sweep = false;      // false: binned plane; true: position in the centroid-sorted order (small nodes)
  uint32_t plane = 0;      // binned: left side = bins [0, plane], right side = bins (plane, bins)
  float cost = 0.0f;       // SA(left)*N(left) + SA(right)*N(right)
  uint32_t leftCount = 0;  // N(left)
};

// Split search for one node. Nodes with fewer triangles than bins use an exact sweep over the triangles
// sorted by centroid (every object split is evaluated; cheaper than clearing and sweeping mostly empty bins,
// and at least as good); larger nodes use the binned search.
class SahBinner {
 public:
  explicit SahBinner(uint32_t bins);

  // Cheapest split; both sides are non-empty. Equal costs prefer the more balanced split.
  SahSplit findBestSplit(const BuildPrimitives& prims, std::span<const uint32_t> ids, const Aabb& centroidBox);

  // Reorders ids so the left side of `split` (the result of the last findBestSplit call, for these ids)
  // comes first; returns its size (= split.leftCount).
  uint32_t partition(const BuildPrimitives& prims, std::span<uint32_t> ids, const Aabb& centroidBox,
                     const SahSplit& split) const;

 private:
  struct Bin {
    Aabb box;
    uint32_t count = 0;
  };
  SahSplit findBinnedSplit(const BuildPrimitives& prims, std::span<const uint32_t> ids, const Aabb& centroidBox);
  SahSplit findSweepSplit(const BuildPrimitives& prims, std::span<const uint32_t> ids);

  uint32_t bins_;
  std::vector<Bin> binData_;          // 3 axes x bins
  std::vector<float> rightArea_;      // suffix sweep: SA of bins (or sorted triangles) [i, end)
  std::vector<uint32_t> rightCount_;  // suffix sweep: count of bins [i, bins)
  std::vector<uint64_t> keys_;        // sweep: (sortable centroid bits << 32 | id) along one axis
  std::vector<uint32_t> bestOrder_;   // sweep: ids in the sorted order of the best axis so far
};

// Balanced fallback split: orders ids around the median centroid along the widest centroid axis and returns
// ids.size() / 2. Always valid, so it is used whenever the SAH split would break the depth bound or no
// SAH plane exists.
uint32_t medianSplit(const BuildPrimitives& prims, std::span<uint32_t> ids, const Aabb& centroidBox);

}  // namespace ht::bvh
