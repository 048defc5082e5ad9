// scene_bvh.cpp - see scene_bvh.h.
#include "gpu/scene_bvh.h"

#include <chrono>
#include <utility>

namespace ht::gpu {
namespace {

bvh::Aabb boundsOf(const Scene& scene) {
  const Bounds3 b = scene.bounds();
  return bvh::Aabb{b.lo, b.hi};
}

}  // namespace

std::vector<bvh::InstanceRange> instanceRanges(const Scene& scene) {
  std::vector<bvh::InstanceRange> out;
  for (const SceneInstance& i : scene.instances()) out.push_back({i.firstTriangle, i.triangleCount, i.mesh});
  return out;
}

SceneBvh flattenedSceneBvh(bvh::GpuBvh bvh) {
  SceneBvh out;
  out.report = bvh.report;
  out.flattened = std::move(bvh);
  return out;
}

SceneBvh buildSceneBvh(const Scene& scene, const bvh::BuildOptions& options, BvhLayoutPolicy policy) {
  const std::vector<bvh::InstanceRange> ranges = instanceRanges(scene);
  if (policy == BvhLayoutPolicy::Flattened || (policy == BvhLayoutPolicy::Automatic && ranges.size() < 2))
    return flattenedSceneBvh(bvh::buildGpuBvh(scene.positions, scene.triangles, options));
  SceneBvh out;
  const auto start = std::chrono::steady_clock::now();
  out.twoLevel = std::make_unique<bvh::TwoLevelBvh>(scene.positions, scene.triangles, ranges, options);
  out.layout = bvh::BvhLayout::TwoLevel;
  out.report.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  out.report.nodeCount = static_cast<uint32_t>(out.twoLevel->blasNodes().size() + out.twoLevel->topNodes().size());
  out.report.trianglesIn = scene.triangles.size();
  if (policy == BvhLayoutPolicy::TwoLevel) return out;
  out.flattened = bvh::buildGpuBvh(scene.positions, scene.triangles, options);
  out.costs = bvh::measureLayoutCosts(out.flattened, *out.twoLevel, bvh::layoutProbeRays(boundsOf(scene)));
  out.costsMeasured = true;
  out.layout = bvh::chooseBvhLayout(false, out.costs);
  if (out.layout == bvh::BvhLayout::TwoLevel) {
    out.flattened = bvh::GpuBvh{};
  } else {
    out.twoLevel.reset();
    out.report = out.flattened.report;
  }
  return out;
}

}  // namespace ht::gpu
