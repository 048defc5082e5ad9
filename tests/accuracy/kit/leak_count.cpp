#include "leak_count.h"

#include <algorithm>

#include "bvh/cpu_traversal.h"
#include "gpu/renderer.h"
#include "naive_moller_trumbore.h"
#include "robust_embree.h"

namespace ht::accuracy {
namespace {

using gpu_shared::HT_MISS;

constexpr size_t kChunk = size_t(1) << 20;  // rays per GPU submission: bounded host and device memory

void countCpu(const TestMesh& mesh, std::span<const gpu_shared::HtRay> rays, LeakCounts& c) {
  const bvh::GpuBvh bvh = bvh::buildGpuBvh(mesh.positions, mesh.triangles, bvh::BuildOptions{});
  c.trianglesDropped = bvh.report.trianglesDropped;
  for (size_t first = 0; first < rays.size(); first += kChunk) {
    const auto part = rays.subspan(first, std::min(kChunk, rays.size() - first));
    for (const auto& r : bvh::traceClosestBatch(bvh, part)) {
      c.cpuMisses += r.hit.triId == HT_MISS ? 1 : 0;
      c.cpuOverflows += r.overflow ? 1 : 0;
    }
  }
}

void countGpu(const TestMesh& mesh, std::span<const gpu_shared::HtRay> rays, gpu::VulkanContext& context,
              LeakCounts& c) {
  gpu::Renderer renderer(context, toScene(mesh));
  for (size_t first = 0; first < rays.size(); first += kChunk) {
    const auto part = rays.subspan(first, std::min(kChunk, rays.size() - first));
    for (const auto& h : renderer.traceClosest(part)) c.gpuMisses += h.triId == HT_MISS ? 1 : 0;
  }
  c.gpuRun = true;
}

void countAnchors(const TestMesh& mesh, std::span<const gpu_shared::HtRay> rays, LeakCounts& c) {
  const RobustEmbree embree(mesh.positions, mesh.triangles);
  for (size_t first = 0; first < rays.size(); first += kChunk) {
    const auto part = rays.subspan(first, std::min(kChunk, rays.size() - first));
    for (const auto& h : embree.traceClosest(part)) c.embreeMisses += h.triId == HT_MISS ? 1 : 0;
  }
  c.mtEpsilonMisses = NaiveMollerTrumbore(mesh.positions, mesh.triangles, MtVariant::Epsilon1em6).countMisses(rays);
  c.mtNoEpsilonMisses = NaiveMollerTrumbore(mesh.positions, mesh.triangles, MtVariant::NoEpsilon).countMisses(rays);
  c.anchorsRun = true;
}

}  // namespace

LeakCounts countLeaks(const TestMesh& mesh, std::span<const gpu_shared::HtRay> rays, const LeakOptions& options) {
  LeakCounts c;
  c.rays = rays.size();
  countCpu(mesh, rays, c);
  if (options.gpu != nullptr) countGpu(mesh, rays, *options.gpu, c);
  if (options.anchors) countAnchors(mesh, rays, c);
  return c;
}

}  // namespace ht::accuracy
