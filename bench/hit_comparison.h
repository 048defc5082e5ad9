// hit_comparison.h - do two tracers agree on the same rays?
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "bvh/ray_types.h"

namespace ht::bench {

struct HitComparison {
  std::uint64_t rays = 0;
  std::uint64_t hitsA = 0, hitsB = 0;   // rays with a hit in A / in B
  std::uint64_t hitMissFlips = 0;       // rays hit by one tracer and missed by the other
  std::uint64_t differentTriangle = 0;  // both hit, different triangles (ties on shared edges are legal)
  double maxRelativeTDiff = 0.0;        // over rays both hit: |tA - tB| / max(tA, tB)
  // |hitsA - hitsB| relative to max(hitsA, hitsB) (0 when neither hit anything).
  double hitCountDifference() const;
};

HitComparison compareClosest(std::span<const gpu_shared::HtHit> a, std::span<const gpu_shared::HtHit> b);
// Same for any-hit results (1 = occluded); the t and triangle fields stay 0.
HitComparison compareOccluded(std::span<const std::uint32_t> a, std::span<const std::uint32_t> b);

}  // namespace ht::bench
