// bvh_layout_choice.cpp - see bvh_layout_choice.h.
#include "bvh/bvh_layout_choice.h"

#include <algorithm>
#include <cmath>

namespace ht::bvh {
namespace {

// Three numbers in [0, 1) for probe ray i, stream k, from a 64-bit LCG step (Knuth's MMIX constants) per draw.
glm::vec3 hashed3(uint32_t i, uint32_t k) {
  uint64_t state = (uint64_t{i} << 32 | k) * 0x9E3779B97F4A7C15ull;
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    out[c] = static_cast<float>(state >> 40) * (1.0f / 16777216.0f);  // 24 bits
  }
  return out;
}

double meanSteps(const std::vector<HtTraceResult>& results) {
  double steps = 0.0;
  for (const HtTraceResult& r : results) steps += r.steps;
  return results.empty() ? 0.0 : steps / static_cast<double>(results.size());
}

}  // namespace

const char* bvhLayoutName(BvhLayout layout) { return layout == BvhLayout::Flattened ? "flattened" : "two-level"; }

std::vector<gpu_shared::HtRay> layoutProbeRays(const Aabb& bounds, uint32_t count) {
  std::vector<gpu_shared::HtRay> rays;
  if (bounds.empty()) return rays;
  const glm::vec3 centre = bounds.lo * 0.5f + bounds.hi * 0.5f;
  const glm::vec3 extent = bounds.hi - bounds.lo;
  const float radius = 0.75f * glm::length(extent) + 1e-6f;
  rays.reserve(count);
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec3 a = hashed3(i, 1u);
    const float z = 2.0f * a.x - 1.0f, phi = 6.2831853f * a.y;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const glm::vec3 origin = centre + radius * glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    const glm::vec3 target = bounds.lo + hashed3(i, 2u) * extent;
    gpu_shared::HtRay ray;
    ray.origin = origin;
    ray.tmin = 0.0f;
    ray.dir = target - origin;
    ray.tmax = INFINITY;
    rays.push_back(ray);
  }
  return rays;
}

LayoutCosts measureLayoutCosts(const GpuBvh& flattened, const TwoLevelBvh& twoLevel,
                               std::span<const gpu_shared::HtRay> probeRays) {
  LayoutCosts costs;
  costs.flattenedStepsPerRay = meanSteps(traceClosestBatch(flattened, probeRays));
  costs.twoLevelStepsPerRay = meanSteps(traceClosestTwoLevelBatch(twoLevel, probeRays));
  return costs;
}

BvhLayout chooseBvhLayout(bool nodesMoved, const LayoutCosts& costs) {
  if (nodesMoved) return BvhLayout::TwoLevel;
  return costs.flattenedStepsPerRay <= costs.twoLevelStepsPerRay ? BvhLayout::Flattened : BvhLayout::TwoLevel;
}

}  // namespace ht::bvh
