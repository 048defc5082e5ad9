// binned_sah.cpp - see binned_sah.h.
#include "bvh/binned_sah.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace ht::bvh {
namespace {

// Maps a centroid coordinate to its bin along one axis: bin = floor((c - lo) * bins / extent), clamped.
struct AxisBinning {
  bool valid = false;
  float lo = 0.0f;
  float scale = 0.0f;
  uint32_t lastBin = 0;

  uint32_t binOf(float c) const {
    float f = (c - lo) * scale;  // in [0, bins * (1 + eps)] for c in the centroid box
    uint32_t bin = f > 0.0f ? static_cast<uint32_t>(f) : 0u;
    return std::min(bin, lastBin);
  }
};

AxisBinning makeAxisBinning(const Aabb& centroidBox, int axis, uint32_t bins) {
  AxisBinning b;
  float extent = centroidBox.hi[axis] - centroidBox.lo[axis];
  float scale = static_cast<float>(bins) / extent;
  // Degenerate axis: no extent, or an extent so small (or so large) that the scale is not a usable number.
  b.valid = extent > 0.0f && std::isfinite(scale) && scale > 0.0f;
  b.lo = centroidBox.lo[axis];
  b.scale = scale;
  b.lastBin = bins - 1;
  return b;
}

// Key whose unsigned order is (centroid coordinate, id): the float's bits made monotonic (negative values
// have all bits flipped, positive ones the sign bit set), then the id in the low half as tie-break.
uint64_t sortKey(float coordinate, uint32_t id) {
  uint32_t bits;
  std::memcpy(&bits, &coordinate, sizeof bits);
  bits = (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
  return (uint64_t{bits} << 32) | id;
}

}  // namespace

NodeBounds computeNodeBounds(const BuildPrimitives& prims, std::span<const uint32_t> ids) {
  NodeBounds nb;
  for (uint32_t id : ids) {
    nb.box.grow(prims.boxes[id]);
    nb.centroidBox.grow(prims.centroids[id]);
  }
  return nb;
}

// True when `candidate` (cost, leftCount) beats `best` for a node of n triangles.
bool betterSplit(const SahSplit& best, float cost, uint32_t leftCount, uint32_t n) {
  if (best.axis < 0 || cost < best.cost) return true;
  if (cost > best.cost) return false;
  auto imbalance = [n](uint32_t left) { return left > n - left ? 2 * left - n : n - 2 * left; };
  return imbalance(leftCount) < imbalance(best.leftCount);
}

SahBinner::SahBinner(uint32_t bins)
    : bins_(bins), binData_(3 * size_t{bins}), rightArea_(bins), rightCount_(bins), keys_(bins), bestOrder_(bins) {}

SahSplit SahBinner::findBestSplit(const BuildPrimitives& prims, std::span<const uint32_t> ids,
                                  const Aabb& centroidBox) {
  return ids.size() < bins_ ? findSweepSplit(prims, ids) : findBinnedSplit(prims, ids, centroidBox);
}

SahSplit SahBinner::findBinnedSplit(const BuildPrimitives& prims, std::span<const uint32_t> ids,
                                    const Aabb& centroidBox) {
  AxisBinning axes[3];
  for (int axis = 0; axis < 3; ++axis) axes[axis] = makeAxisBinning(centroidBox, axis, bins_);
  std::fill(binData_.begin(), binData_.end(), Bin{});

  for (uint32_t id : ids) {
    const glm::vec3& c = prims.centroids[id];
    const Aabb& box = prims.boxes[id];
    for (int axis = 0; axis < 3; ++axis) {
      if (!axes[axis].valid) continue;
      Bin& bin = binData_[axis * bins_ + axes[axis].binOf(c[axis])];
      bin.box.grow(box);
      ++bin.count;
    }
  }

  const uint32_t n = static_cast<uint32_t>(ids.size());
  SahSplit best;
  for (int axis = 0; axis < 3; ++axis) {
    if (!axes[axis].valid) continue;
    const Bin* bins = &binData_[axis * bins_];
    // Suffix sweep: area and count of bins [i, bins).
    Aabb right;
    uint32_t rightN = 0;
    for (uint32_t i = bins_ - 1; i > 0; --i) {
      right.grow(bins[i].box);
      rightN += bins[i].count;
      rightArea_[i] = right.halfArea();
      rightCount_[i] = rightN;
    }
    // Prefix sweep: plane p separates bins [0, p] from (p, bins).
    Aabb left;
    uint32_t leftN = 0;
    for (uint32_t p = 0; p + 1 < bins_; ++p) {
      left.grow(bins[p].box);
      leftN += bins[p].count;
      if (leftN == 0 || rightCount_[p + 1] == 0) continue;
      float cost =
          left.halfArea() * static_cast<float>(leftN) + rightArea_[p + 1] * static_cast<float>(rightCount_[p + 1]);
      if (betterSplit(best, cost, leftN, n)) best = SahSplit{axis, false, p, cost, leftN};
    }
  }
  return best;
}

SahSplit SahBinner::findSweepSplit(const BuildPrimitives& prims, std::span<const uint32_t> ids) {
  const uint32_t n = static_cast<uint32_t>(ids.size());
  std::span<uint64_t> keys(keys_.data(), n);
  SahSplit best;
  for (int axis = 0; axis < 3; ++axis) {
    for (uint32_t i = 0; i < n; ++i) keys[i] = sortKey(prims.centroids[ids[i]][axis], ids[i]);
    std::sort(keys.begin(), keys.end());
    Aabb right;
    for (uint32_t i = n - 1; i > 0; --i) {
      right.grow(prims.boxes[static_cast<uint32_t>(keys[i])]);
      rightArea_[i] = right.halfArea();
    }
    Aabb left;
    const int bestAxisBefore = best.axis;
    for (uint32_t i = 0; i + 1 < n; ++i) {
      left.grow(prims.boxes[static_cast<uint32_t>(keys[i])]);
      const uint32_t leftN = i + 1;
      float cost = left.halfArea() * static_cast<float>(leftN) + rightArea_[i + 1] * static_cast<float>(n - leftN);
      if (betterSplit(best, cost, leftN, n)) best = SahSplit{axis, true, 0, cost, leftN};
    }
    if (best.axis != bestAxisBefore) {
      for (uint32_t i = 0; i < n; ++i) bestOrder_[i] = static_cast<uint32_t>(keys[i]);
    }
  }
  return best;
}

uint32_t SahBinner::partition(const BuildPrimitives& prims, std::span<uint32_t> ids, const Aabb& centroidBox,
                              const SahSplit& split) const {
  if (split.sweep) {
    std::copy(bestOrder_.begin(), bestOrder_.begin() + static_cast<std::ptrdiff_t>(ids.size()), ids.begin());
    return split.leftCount;
  }
  AxisBinning binning = makeAxisBinning(centroidBox, split.axis, bins_);
  auto middle = std::partition(ids.begin(), ids.end(), [&](uint32_t id) {
    return binning.binOf(prims.centroids[id][split.axis]) <= split.plane;
  });
  return static_cast<uint32_t>(middle - ids.begin());
}

uint32_t medianSplit(const BuildPrimitives& prims, std::span<uint32_t> ids, const Aabb& centroidBox) {
  glm::vec3 extent = centroidBox.hi - centroidBox.lo;
  int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
  const uint32_t half = static_cast<uint32_t>(ids.size() / 2);
  std::nth_element(ids.begin(), ids.begin() + half, ids.end(), [&](uint32_t a, uint32_t b) {
    float ca = prims.centroids[a][axis];
    float cb = prims.centroids[b][axis];
    return ca < cb || (ca == cb && a < b);  // total order: deterministic for equal centroids
  });
  return half;
}

}  // namespace ht::bvh
