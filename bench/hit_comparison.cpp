// hit_comparison.cpp - see hit_comparison.h.
#include "bench/hit_comparison.h"

#include <algorithm>
#include <cmath>

namespace ht::bench {

double HitComparison::hitCountDifference() const {
  const double larger = double(std::max(hitsA, hitsB));
  return larger > 0.0 ? std::abs(double(hitsA) - double(hitsB)) / larger : 0.0;
}

HitComparison compareClosest(std::span<const gpu_shared::HtHit> a, std::span<const gpu_shared::HtHit> b) {
  HitComparison c;
  c.rays = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < c.rays; ++i) {
    const bool hitA = a[i].triId != gpu_shared::HT_MISS, hitB = b[i].triId != gpu_shared::HT_MISS;
    c.hitsA += hitA;
    c.hitsB += hitB;
    c.hitMissFlips += hitA != hitB;
    if (!hitA || !hitB) continue;
    c.differentTriangle += a[i].triId != b[i].triId;
    const double larger = std::max(std::abs(double(a[i].t)), std::abs(double(b[i].t)));
    if (larger > 0.0) c.maxRelativeTDiff = std::max(c.maxRelativeTDiff, std::abs(double(a[i].t) - b[i].t) / larger);
  }
  return c;
}

HitComparison compareOccluded(std::span<const std::uint32_t> a, std::span<const std::uint32_t> b) {
  HitComparison c;
  c.rays = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < c.rays; ++i) {
    c.hitsA += a[i] != 0;
    c.hitsB += b[i] != 0;
    c.hitMissFlips += (a[i] != 0) != (b[i] != 0);
  }
  return c;
}

}  // namespace ht::bench
