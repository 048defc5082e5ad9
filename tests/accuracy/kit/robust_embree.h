// robust_embree.h - Embree 3 with RTC_SCENE_FLAG_ROBUST (watertight Plücker test, conservative traversal;
// docs/BVH.md §2.1), the anchor of the differential tests. Single-ray rtcIntersect1 over all cores.
#pragma once
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/ray_types.h"

namespace ht::accuracy {

class RobustEmbree {
 public:
  RobustEmbree(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles);
  ~RobustEmbree();
  RobustEmbree(const RobustEmbree&) = delete;
  RobustEmbree& operator=(const RobustEmbree&) = delete;
  // HtHit conventions: triId = HT_MISS and t = tmax on a miss; u, v barycentrics of vertices 1 and 2.
  std::vector<gpu_shared::HtHit> traceClosest(std::span<const gpu_shared::HtRay> rays) const;

  struct Handles;

 private:
  std::unique_ptr<Handles> handles_;
};

}  // namespace ht::accuracy
