// ray_batches.cpp - rays without a frame: the primary rays raygen writes for a range of targets, read back
// untraced, and closest-hit / any-hit traces of a user batch (parity tests, `holotrace rays`, `raycast`, benchmarks).
#include <algorithm>
#include <array>
#include <cstring>

#include "gpu/renderer_impl.h"

namespace ht::gpu {

std::vector<gpu_shared::HtRay> Renderer::Impl::generateRays(const FrameCamera& camera, const RenderSettings& settings,
                                                            std::uint64_t firstTarget, std::uint32_t targetCount,
                                                            TraceStats* stats) {
  checkSettings(settings);
  const FrameShape shape = frameShape(camera);
  checkShape(shape, settings.spp);
  if (firstTarget + targetCount > shape.targets()) {
    throw GpuError("targets [" + std::to_string(firstTarget) + ", " + std::to_string(firstTarget + targetCount) +
                   ") outside the camera's " + std::to_string(shape.targets()));
  }
  const std::uint64_t totalPaths = static_cast<std::uint64_t>(targetCount) * settings.spp;
  std::vector<gpu_shared::HtRay> rays(totalPaths);
  const std::uint64_t perBatch = std::max<std::uint64_t>(settings.spp, kMaxPathsPerBatch / settings.spp * settings.spp);
  work.ensure(vk, static_cast<std::uint32_t>(std::min(perBatch, std::max<std::uint64_t>(totalPaths, 1))), 1);
  if (outputs.generation == 0) outputs.ensure(vk, 1, 1);  // raygen writes no outputs; the views need a buffer
  bindState();
  fillFrame(camera, shape, RowBand{0, shape.height}, 0, shape.views, settings);
  const ComputePipeline& raygen = pipeline(ShaderId::Raygen, raygenSpec(camera, shape));
  std::array<double, static_cast<size_t>(Stage::Count)> stageMs{};
  for (std::uint64_t begin = 0; begin < totalPaths; begin += perBatch) {
    const auto count = static_cast<std::uint32_t>(std::min(perBatch, totalPaths - begin));
    const auto batchFirst = static_cast<std::uint32_t>(firstTarget * settings.spp + begin);
    beginCommands();
    PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
    rec.dispatch(raygen, passConstants(batchFirst, count, 0, 0), groupsFor(count), Stage::Raygen);
    submitAndWait();
    rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
    work.rays[0].download(rays.data() + begin, count * sizeof(gpu_shared::HtRay));
  }
  if (stats) stats->gpuMs = stageMs[static_cast<size_t>(Stage::Raygen)];
  return rays;
}

std::vector<gpu_shared::HtHit> Renderer::Impl::traceBatch(std::span<const gpu_shared::HtRay> rays, bool occlusion,
                                                          TraceStats* stats) {
  std::vector<gpu_shared::HtHit> hits(rays.size());
  const auto chunk =
      static_cast<std::uint32_t>(std::min<std::uint64_t>(kMaxPathsPerBatch * 4ull, std::max<size_t>(rays.size(), 1)));
  work.ensure(vk, chunk, 1);
  if (outputs.generation == 0) outputs.ensure(vk, 1, 1);  // the trace kernels write no outputs; views need a buffer
  const ComputePipeline& trace =
      occlusion ? pipeline(ShaderId::TraceAny, traceSpec({0u})) : pipeline(ShaderId::TraceClosest, traceSpec({}));
  FrameBlock& f = frameBlock();
  std::memset(&f, 0, sizeof(f));
  fillFrameBasics(f);
  bindState();
  f.scene = glm::uvec4(0u, 0u, gpu_shared::HT_TRAVERSAL_STEP_LIMIT, 0u);
  std::array<double, static_cast<size_t>(Stage::Count)> stageMs{};
  std::uint32_t maxSteps = 0;
  for (size_t begin = 0; begin < rays.size(); begin += chunk) {
    const auto count = static_cast<std::uint32_t>(std::min<size_t>(chunk, rays.size() - begin));
    work.rays[0].upload(rays.data() + begin, count * sizeof(gpu_shared::HtRay));
    std::memset(counters.mapped(), 0, sizeof(GpuCounters));
    counterBlock().queueCount[0] = count;
    beginCommands();
    PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
    rec.dispatch(trace, passConstants(0, count, 0, 0), groupsFor(count), Stage::Trace);
    submitAndWait();
    rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
    checkCounters(occlusion ? "traceOccluded" : "traceClosest");
    maxSteps = std::max(maxSteps, counterBlock().maxSteps);
    work.hits.download(hits.data() + begin, count * sizeof(gpu_shared::HtHit));
  }
  if (stats) {
    stats->gpuMs = stageMs[static_cast<size_t>(Stage::Trace)];
    stats->maxSteps = maxSteps;
  }
  return hits;
}

}  // namespace ht::gpu
