// accumulation_pass.cpp - progressive accumulation (gpu/accumulator.h, docs/REUSE.md §1-§2): the accumulation's
// identity and device buffers, one progressive frame over the chunks of the wavefront loop, and the show pass that
// turns the stored sums into the frame (sum / n) and the stop rule's statistics.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "gpu/accumulation_error.h"
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

// Segment cells are recorded per chunk target: only a frame that is one chunk of the whole frame records them under
// the frame-global index the sums use (wavefront_loop.cpp cuts large view arrays into chunks).
bool recordsWholeFrame(const FrameShape& frame, const RenderSettings& settings) {
  const RenderRegion& r = settings.region;
  const bool whole = r.viewFirst == 0 && r.rowFirst == 0 && (r.viewCount == 0 || r.viewCount == frame.views) &&
                     (r.rowCount == 0 || r.rowCount == frame.height);
  const std::uint64_t viewPixels = std::uint64_t{frame.width} * frame.height;
  return whole && kMaxChunkPixels / viewPixels >= frame.views;
}

}  // namespace

Accumulator::Accumulator(const AccumulationPolicy& policy) : policy_(policy), state_(std::make_unique<State>()) {}
Accumulator::~Accumulator() = default;
std::uint64_t Accumulator::deviceBytes() const {
  return state_->sums.size() + state_->halves.size() + state_->masks.size() + state_->list.size();
}
void Accumulator::restart() { state_->key.clear(); }

std::vector<std::uint32_t> Accumulator::downloadMasks() const {
  std::vector<std::uint32_t> masks;
  if (!state_->masksValid) return masks;
  masks.resize(state_->masks.size() / sizeof(std::uint32_t));
  state_->masks.download(masks.data(), state_->masks.size());
  return masks;
}

std::vector<std::uint32_t> Accumulator::lastResetTargets() const {
  if (report_.resetTargets == 0) return {};
  const auto* list = static_cast<const std::uint32_t*>(state_->dirty.mapped());
  return {list + FrameReuseState::kListFirst, list + FrameReuseState::kListFirst + list[2]};
}

std::vector<float> Accumulator::downloadSums() const {
  struct Plane {  // sum and n, or halfSum and halfN
    glm::vec3 sum;
    std::uint32_t n;
  };
  const std::size_t count = state_->sums.size() / sizeof(Plane);
  std::vector<Plane> whole(count), half(count);
  if (count > 0) {
    state_->sums.download(whole.data(), count * sizeof(Plane));
    state_->halves.download(half.data(), count * sizeof(Plane));
  }
  std::vector<float> sums;
  sums.reserve(count * 8);
  for (std::size_t t = 0; t < count; ++t) {
    for (float v : {whole[t].sum.x, whole[t].sum.y, whole[t].sum.z, float(whole[t].n), half[t].sum.x, half[t].sum.y,
                    half[t].sum.z, float(half[t].n)})
      sums.push_back(v);
  }
  return sums;
}

std::string accumulationKey(const void* renderer, const FrameCamera& camera, const RenderSettings& settings) {
  std::string key;
  appendBytes(key, renderer);
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
  f.accumStats = accumulator.state().stats.address();
  f.accumSettledStats = accumulator.state().stats.address() + sizeof(gpu_shared::AccumStats);
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
  if (frame.targets() > vk.info.maxTexelBufferElements) {
    throw GpuError("a progressive accumulation of " + std::to_string(frame.targets()) +
                   " targets exceeds the device's texel buffers (" + std::to_string(vk.info.maxTexelBufferElements) +
                   " elements, one per target): render independent frames or a smaller panel");
  }
  Accumulator::State& st = accumulator.state();
  AccumulationReport& report = accumulator.mutableReport();
  const std::string key = accumulationKey(this, camera, settings);
  // Same view and settings, and only node moves since the sums' scene version: restart the targets near them.
  const bool sameView = !st.key.empty() && st.key == key;
  std::optional<Bounds3> moved;
  if (sameView && st.generation != sceneGeneration && st.masksValid) moved = movedSince(st.generation);
  const bool restart = !sameView || (st.generation != sceneGeneration && !moved);
  st.pendingMove.reset();
  if (moved && !moved->empty()) st.pendingMove = moved;
  if (restart) {
    st.key.clear();
    st.masksValid = false;
    const VkDeviceSize bytes = static_cast<VkDeviceSize>(frame.targets()) * (sizeof(gpu_shared::AccumTarget) / 2);
    // kMaskWords per target, then the bounds of each target's primary segments (common.glsl accum_reach_word), in
    // whole 16-byte texels (the marking pass reads them through an RGBA32UI view)
    const VkDeviceSize maskBytes =
        (static_cast<VkDeviceSize>(frame.targets()) * (kMaskWords + kAccumulationBoundWords) * sizeof(std::uint32_t) +
         15) /
        16 * 16;
    if (st.sums.size() != bytes) {
      st.sums = DeviceBuffer();  // the old sums go before the new ones are allocated
      st.halves = DeviceBuffer();
      st.masks = DeviceBuffer();
      st.list = DeviceBuffer();
      st.sums = DeviceBuffer(vk, bytes, MemoryPlace::Device);
      st.halves = DeviceBuffer(vk, bytes, MemoryPlace::Device);
      st.masks = DeviceBuffer(vk, maskBytes, MemoryPlace::Device);  // counted in bytesFor whether used or not
    }
    OneShotCommands zero(vk);
    vkCmdFillBuffer(zero.cmd(), st.sums.handle(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(zero.cmd(), st.halves.handle(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(zero.cmd(), st.masks.handle(), 0, VK_WHOLE_SIZE, 0);
    zero.submitAndWait();
    // Recording costs a pass per depth (about 12 % of a progressive frame on lavapipe), so only scenes whose nodes
    // move record: the ones on the two-level BVH (a node move puts a scene there; static scenes stay flattened).
    // (The marking pass reads the masks through a texel view: they must fit the device's texel-buffer limit.)
    st.masksValid = recordsWholeFrame(frame, settings) && scene.layout() == bvh::BvhLayout::TwoLevel &&
                    maskBytes / 16 <= vk.info.maxTexelBufferElements;
    // the frame's statistics, then the settled targets' (FrameBlock::accumSettledStats)
    if (st.stats.size() == 0) {
      st.stats = DeviceBuffer(vk, 2 * sizeof(gpu_shared::AccumStats), MemoryPlace::HostReadback);
    }
    report = AccumulationReport{};
  }
  constexpr gpu_shared::AccumStats kNoTargets{0u, 0u, std::numeric_limits<std::uint32_t>::max(), 0u};
  auto* stats = static_cast<gpu_shared::AccumStats*>(st.stats.mapped());
  stats[0] = kNoTargets;
  // The last frame's list stands for the targets that may still need samples, unless targets started over since.
  if (restart || st.pendingMove) st.listed.reset();
  if (!st.listed) stats[1] = kNoTargets;  // this frame judges every target
  report.restarted = restart;
  report.tracedTargets = 0;
  report.resetTargets = 0;
  accumulating = &accumulator;
  bindAccumulation(&st);
  RenderResult result;
  try {
    result = render(camera, settings);
  } catch (...) {
    accumulating = nullptr;  // the sums may hold part of a frame: the next frame starts over
    st.key.clear();
    st.listed.reset();
    try {
      bindAccumulation(nullptr);
    } catch (const std::exception&) {  // (the render's own error is the one reported)
    }
    throw;
  }
  accumulating = nullptr;
  bindAccumulation(nullptr);  // the accumulation's buffers may go before the next one binds its own
  st.key = key;
  st.generation = sceneGeneration;
  report.targets = std::uint64_t{result.width} * result.height * result.views * frame.targetsPerPixel;
  // The targets the frame showed, and those it did not (settled earlier: their sums did not change since).
  report.unconverged = stats[0].unconverged + stats[1].unconverged;
  report.maxError = glm::uintBitsToFloat(std::max(stats[0].maxErrorBits, stats[1].maxErrorBits));
  report.minSamples = std::min(stats[0].minSamples, stats[1].minSamples);
  report.maxSamples = std::max(stats[0].maxSamples, stats[1].maxSamples);
  report.frames += 1;
  report.converged = report.unconverged == 0;
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
  Accumulator::State& st = accumulator.state();
  const bool reset = st.pendingMove.has_value();
  if (reset) {
    accumulator.mutableReport().resetTargets =
        resetMovedTargets(accumulator, *st.pendingMove, camera, shape, targets, stageMs);
    st.pendingMove.reset();
  }
  // Every pass of the accumulation ORs its segments' cells into the accumulation's masks (cleared at its restart).
  const bool record = st.masksValid;
  if (record) {
    frameBlock().segmentMasks = st.masks.address();
    frameBlock().grid = reuse.grid();
  }
  framePlan.recordSegments = record;
  const std::uint32_t spp = settings.spp;
  const auto progress = [&](double done) {
    if (settings.progress) settings.progress(done);
  };
  // The first frame samples every target; later ones, under the adaptive policy, the targets that need samples.
  std::uint64_t sampled = targets;
  if (!accumulator.policy().adaptive || accumulator.report().frames == 0) {
    tracePaths(camera, shape, spp, targets * spp, perBatch, TracedTargets::All, settings, stageMs, progress);
    st.listed.reset();
  } else {
    if (viewCount == shape.views) {  // one chunk: keep the list for the next frame
      const VkDeviceSize listBytes = targets * sizeof(std::uint32_t);
      if (st.list.size() != listBytes) st.list = DeviceBuffer(vk, listBytes, MemoryPlace::Device);
      frameBlock().accumList = st.list.address();
    }
    // Among the last list's entries (an invocation each) while they are fewer than the chunk's pixels (an
    // invocation each, over all targets). Judging every target is always right: the targets left out before are
    // left out again, and their statistics fold into the settled ones a second time, which changes no maximum,
    // minimum or count of targets that need samples (none of them do).
    const std::uint64_t pixels = targets / shape.targetsPerPixel;
    std::optional<std::uint64_t> among = st.listed;
    if (among && *among >= pixels) among.reset();
    sampled = selectUnconvergedTargets(shape, targets, among, stageMs);
    st.listed.reset();
    if (frameBlock().accumList != 0) st.listed = sampled;
    if (sampled > 0) {
      frameBlock().refineInfo.w = spp;  // != 0: shade keys the listed targets' paths through the list
      tracePaths(camera, shape, spp, sampled * spp, std::min(perBatch, sampled * spp), TracedTargets::Refined, settings,
                 stageMs, progress);
    }
  }
  accumulator.mutableReport().tracedTargets += sampled;
  // Only the sampled targets' values changed. Show only them while the subpixel buffer still holds this
  // accumulation's last frame: no other chunk ran since, and no target started over (a reset target is sampled,
  // unless a stop rule with an unreachable target error leaves it out).
  const bool showListed =
      st.listed && !reset && st.shownChunk + 1 == chunksRendered && st.shownOutputs == outputs.generation;
  showTargets(shape.model, showListed ? sampled : targets, showListed, stageMs);
  st.shownChunk = chunksRendered;
  st.shownOutputs = outputs.generation;
  framePlan.recordSegments = false;  // the renderer's own reuse state recorded nothing (frameDone)
}

void Renderer::Impl::showTargets(std::uint32_t model, std::uint64_t count, bool listed, StageTimes& stageMs) {
  if (count == 0) return;
  const ComputePipeline& show = pipeline(ShaderId::AccumShow, {model, listed ? 1u : 0u});
  constexpr std::uint32_t perInvocation = gpu_shared::HT_ACCUM_SHOW_TARGETS_PER_INVOCATION;
  const std::uint64_t perDispatch = std::uint64_t{kMaxGroupsPerDispatch} * HT_WORKGROUP_SIZE * perInvocation;
  beginCommands();
  PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
  for (std::uint64_t first = 0; first < count; first += perDispatch) {
    const auto slice = static_cast<std::uint32_t>(std::min(perDispatch, count - first));
    rec.dispatch(show, passConstants(static_cast<std::uint32_t>(first), slice, 0, 0),
                 groupsFor((slice + perInvocation - 1) / perInvocation), Stage::Resolve);
  }
  submitAndWait();
  rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
}

std::uint64_t Renderer::Impl::resetMovedTargets(Accumulator& accumulator, const Bounds3& moved,
                                                const FrameCamera& camera, const FrameShape& shape,
                                                std::uint64_t targets, StageTimes& stageMs) {
  Accumulator::State& st = accumulator.state();
  // The header, the dirty targets, then the candidates of the exact primary test (at most one entry per target each)
  const VkDeviceSize listBytes = (FrameReuseState::kListFirst + 2 * targets) * sizeof(std::uint32_t);
  if (st.dirty.size() < listBytes) st.dirty = DeviceBuffer(vk, listBytes, MemoryPlace::HostReadback);
  auto* list = static_cast<std::uint32_t*>(st.dirty.mapped());
  const gpu_shared::uvec2 cellMask = gpu_shared::ht_grid_bounds_mask(moved.lo, moved.hi, reuse.grid());
  const std::uint32_t cells[2] = {cellMask.x, cellMask.y};
  const Bounds3 padded = paddedMovedBounds(moved, reuse.grid());
  FrameBlock& f = frameBlock();
  FrameReuseState::writeMarkingInputs(list, f, cells, padded.lo, padded.hi,
                                      static_cast<std::uint32_t>(FrameReuseState::kListFirst + targets), 0u, kNoBalls);
  f.segmentMasks = st.masks.address();
  f.grid = reuse.grid();
  f.primaryRays = 0;  // no cached primary rays or hits: mark_accumulated.comp generates the rays again
  f.primaryHits = 0;
  f.refine = st.dirty.address();
  f.refineInfo = glm::uvec4(0u, FrameReuseState::kListFirst, 0u, 0u);
  const std::vector<std::uint32_t> spec = raygenSpec(camera, shape);
  const ComputePipeline& exact = pipeline(ShaderId::MarkAccumulated, {spec[0], spec[1], spec[2]});
  runMarkingPass(targets, true, list, st.masks, stageMs, {}, &exact);
  f.refine = 0;
  f.refineInfo = glm::uvec4(0u);
  return list[2];
}

}  // namespace ht::gpu
