// accumulation_pass.cpp - progressive accumulation (gpu/accumulator.h, docs/REUSE.md §1-§2): the accumulation's
// identity and device buffers, one progressive frame over the chunks of the wavefront loop, and the show pass that
// turns the stored sums into the frame (sum / n) and the stop rule's statistics.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "gpu/renderer_impl.h"

namespace ht::gpu {

namespace {

constexpr std::uint32_t kMaxGroupsPerDispatch = 65535;  // the minimum maxComputeWorkGroupCount[0] (lavapipe's)

void checkPolicy(const AccumulationPolicy& policy) {
  if (policy.maxSpp < 1 || policy.minSpp > policy.maxSpp) {
    throw GpuError("accumulation stop rule: min spp " + std::to_string(policy.minSpp) + " and max spp " +
                   std::to_string(policy.maxSpp) + " need 1 <= max spp and min spp <= max spp");
  }
  if (!(policy.targetError >= 0.0f) || !std::isfinite(policy.targetError)) {
    throw GpuError("accumulation target error " + std::to_string(policy.targetError) + " must be a finite number >= 0");
  }
}

// Appends the bytes of a trivially copyable value.
template <typename T>
void appendBytes(std::string& key, const T& value) {
  key.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

}  // namespace

Accumulator::Accumulator(const AccumulationPolicy& policy) : policy_(policy), state_(std::make_unique<State>()) {}
Accumulator::~Accumulator() = default;
std::uint64_t Accumulator::deviceBytes() const { return state_->targets.size(); }
void Accumulator::restart() { state_->key.clear(); }

std::vector<float> Accumulator::downloadSums() const {
  std::vector<gpu_shared::AccumTarget> targets(state_->targets.size() / sizeof(gpu_shared::AccumTarget));
  if (!targets.empty()) state_->targets.download(targets.data(), targets.size() * sizeof(gpu_shared::AccumTarget));
  std::vector<float> sums;
  sums.reserve(targets.size() * 8);
  for (const gpu_shared::AccumTarget& t : targets) {
    for (float v : {t.sum.x, t.sum.y, t.sum.z, float(t.n), t.halfSum.x, t.halfSum.y, t.halfSum.z, float(t.halfN)})
      sums.push_back(v);
  }
  return sums;
}

std::string accumulationKey(const void* renderer, std::uint64_t sceneGeneration, const FrameCamera& camera,
                            const RenderSettings& settings) {
  std::string key;
  appendBytes(key, renderer);
  appendBytes(key, sceneGeneration);
  const auto* table = std::get_if<RayTableCamera>(&camera);
  appendBytes(key, static_cast<const void*>(table ? table->table.get() : nullptr));
  const gpu_shared::CameraBlock block = cameraBlock(camera);  // every byte set (frame_camera.h)
  appendBytes(key, block);
  const FrameShape shape = frameShape(camera);
  for (std::uint32_t v : {shape.model, shape.width, shape.height, shape.views, shape.targetsPerPixel,
                          static_cast<std::uint32_t>(settings.filter), settings.maxDepth,
                          settings.forceAllFeatures ? 1u : 0u, settings.seed, settings.region.viewFirst,
                          settings.region.viewCount, settings.region.rowFirst, settings.region.rowCount}) {
    appendBytes(key, v);
  }
  return key;
}

void Renderer::Impl::fillAccumulation(FrameBlock& f, Accumulator& accumulator) const {
  f.accumTargets = accumulator.state().targets.address();
  f.accumStats = accumulator.state().stats.address();
  const AccumulationPolicy& p = accumulator.policy();
  f.accum = glm::uvec4(1u, glm::floatBitsToUint(p.targetError), p.minSpp, p.maxSpp);
}

RenderResult Renderer::Impl::accumulate(const FrameCamera& camera, const RenderSettings& settings,
                                        Accumulator& accumulator) {
  checkSettings(settings);
  checkPolicy(accumulator.policy());
  if (settings.refineSpp != 0) {
    throw GpuError("progressive frames take no refinement spp (" + std::to_string(settings.refineSpp) +
                   "): the accumulation's adaptive policy decides where samples go");
  }
  const FrameShape frame = frameShape(camera);
  checkShape(frame, settings.spp);
  Accumulator::State& st = accumulator.state();
  AccumulationReport& report = accumulator.mutableReport();
  const std::string key = accumulationKey(this, sceneGeneration, camera, settings);
  const bool restart = st.key != key;
  if (restart) {
    st.key.clear();
    const VkDeviceSize bytes = Accumulator::bytesFor(frame);
    if (st.targets.size() != bytes) {
      st.targets = DeviceBuffer();  // the old sums go before the new ones are allocated
      st.targets = DeviceBuffer(vk, bytes, MemoryPlace::Device);
    }
    OneShotCommands zero(vk);
    vkCmdFillBuffer(zero.cmd(), st.targets.handle(), 0, VK_WHOLE_SIZE, 0);
    zero.submitAndWait();
    if (st.stats.size() == 0) st.stats = DeviceBuffer(vk, sizeof(gpu_shared::AccumStats), MemoryPlace::HostReadback);
    report = AccumulationReport{};
  }
  auto& stats = *static_cast<gpu_shared::AccumStats*>(st.stats.mapped());
  stats = gpu_shared::AccumStats{0u, 0u, std::numeric_limits<std::uint32_t>::max(), 0u};
  report.restarted = restart;
  report.tracedTargets = 0;
  accumulating = &accumulator;
  RenderResult result;
  try {
    result = render(camera, settings);
  } catch (...) {
    accumulating = nullptr;  // the sums may hold part of a frame: the next frame starts over
    throw;
  }
  accumulating = nullptr;
  st.key = key;
  report.targets = std::uint64_t{result.width} * result.height * result.views * frame.targetsPerPixel;
  report.unconverged = stats.unconverged;
  report.maxError = glm::uintBitsToFloat(stats.maxErrorBits);
  report.minSamples = stats.minSamples;
  report.maxSamples = stats.maxSamples;
  report.frames += 1;
  report.converged = stats.unconverged == 0;
  result.accumulation = report;
  return result;
}

void Renderer::Impl::accumulateChunk(const FrameCamera& camera, const FrameShape& shape, const RowBand& /*band*/,
                                     std::uint32_t /*viewFirst*/, std::uint32_t viewCount,
                                     const RenderSettings& settings, std::uint64_t perBatch, StageTimes& stageMs,
                                     RenderResult& /*result*/) {
  Accumulator& accumulator = *accumulating;
  const std::uint64_t targets =
      static_cast<std::uint64_t>(shape.width) * shape.height * viewCount * shape.targetsPerPixel;
  fillAccumulation(frameBlock(), accumulator);
  const std::uint32_t spp = settings.spp;
  const auto progress = [&](double done) {
    if (settings.progress) settings.progress(done);
  };
  // The first frame samples every target; later ones, under the adaptive policy, the targets that need samples.
  if (!accumulator.policy().adaptive || accumulator.report().frames == 0) {
    tracePaths(camera, shape, spp, targets * spp, perBatch, TracedTargets::All, settings, stageMs, progress);
    accumulator.mutableReport().tracedTargets += targets;
  } else {
    const std::uint64_t listed = selectRefinedTargets(shape, targets, 0.0f, stageMs, true);
    accumulator.mutableReport().tracedTargets += listed;
    if (listed > 0) {
      frameBlock().refineInfo.w = spp;  // != 0: shade keys the listed targets' paths through the list
      tracePaths(camera, shape, spp, listed * spp, std::min(perBatch, listed * spp), TracedTargets::Refined, settings,
                 stageMs, progress);
    }
  }
  const ComputePipeline& show = pipeline(ShaderId::AccumShow, {shape.model});
  const std::uint64_t perDispatch = std::uint64_t{kMaxGroupsPerDispatch} * HT_WORKGROUP_SIZE;
  beginCommands();
  PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
  for (std::uint64_t first = 0; first < targets; first += perDispatch) {
    const auto count = static_cast<std::uint32_t>(std::min(perDispatch, targets - first));
    rec.dispatch(show, passConstants(static_cast<std::uint32_t>(first), count, 0, 0), groupsFor(count), Stage::Resolve);
  }
  submitAndWait();
  rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
}

}  // namespace ht::gpu
