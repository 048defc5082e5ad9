// partial_retrace.cpp - the frame-reuse side of the wavefront loop (gpu/frame_reuse.h, docs/REUSE.md §3-4): the key
// that says whether two frames trace the same primary rays, and the partial re-render after a node move: the marking
// pass lists the targets whose recorded segment cells meet the moved bounds, and only those are traced again
// through the listed-target pipelines the adaptive refinement uses; every other target keeps its value in the
// subpixel buffer.
#include <algorithm>
#include <cstring>

#include "gpu/renderer_impl.h"

namespace ht::gpu {

namespace {

template <typename T>
void appendBytes(std::vector<std::byte>& out, const T& value) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

// Targets per marking (and listed interleave) dispatch: within the 65,535 workgroups a dispatch dimension is
// guaranteed.
constexpr std::uint64_t kMarkTargetsPerDispatch = 1ull << 21;
// mark_dirty.comp's MODE.
constexpr std::uint32_t kMarkTargets = 0, kMarkSecondaryEntries = 1, kMarkCandidates = 2;

}  // namespace

ReuseKey Renderer::Impl::reuseKey(const RenderSettings& settings) const {
  ReuseKey key;
  appendBytes(key.bytes, *static_cast<const FrameBlock*>(frame.mapped()));
  appendBytes(key.bytes, settings.forceAllFeatures);
  appendBytes(key.bytes, settings.maxPathsPerBatch);  // the caches are laid out by batch
  appendBytes(key.bytes, boundRayTable.get());
  return key;
}

std::uint64_t Renderer::Impl::markMovedTargets(std::uint64_t targets, StageTimes& stageMs) {
  auto* list = static_cast<std::uint32_t*>(reuse.dirtyList.mapped());
  std::vector<FrameReuseState::SecondaryQueue> secondary;
  if (framePlan.secondaryExact) secondary = reuse.secondaryQueues();
  FrameBlock& f = frameBlock();
  // The candidates of the exact tests follow the dirty entries (none without the primary cache).
  FrameReuseState::writeMarkingInputs(
      list, f, framePlan.gridCells, framePlan.movedLo, framePlan.movedHi,
      framePlan.primaryCached ? static_cast<std::uint32_t>(FrameReuseState::kListFirst + targets) : 0u,
      framePlan.secondaryExact ? static_cast<std::uint32_t>(reuse.secondaryEntries()) : 0u, framePlan.movedBalls);
  writeWalkedInstances(f);
  f.refine = reuse.dirtyList.address();
  f.refineInfo = glm::uvec4(0u, FrameReuseState::kListFirst, 0u, 0u);
  runMarkingPass(targets, false, list, reuse.segmentMasks, stageMs, secondary);
  f.refine = 0;
  f.refineInfo = glm::uvec4(0u);
  return list[2];
}

void Renderer::Impl::writeWalkedInstances(FrameBlock& f) const {
  static_assert(gpu_shared::HT_MAX_WALKED_INSTANCES == 4, "the instance indices fill one uvec4");
  f.movedInstanceIds = glm::uvec4(~0u);
  const bvh::TwoLevelBvh* twoLevel = scene.twoLevel();
  if (!movedInstanceWalks || scene.layout() != bvh::BvhLayout::TwoLevel || twoLevel == nullptr) return;
  const std::vector<std::uint32_t>& moved = framePlan.walkedInstances;  // at most HT_MAX_WALKED_INSTANCES
  if (std::any_of(moved.begin(), moved.end(), [&](std::uint32_t i) { return i >= twoLevel->instanceCount(); }))
    return;  // not this BVH's: trace those rays whole
  for (std::size_t k = 0; k < moved.size(); ++k) {
    const bvh::InstanceRange& range = twoLevel->instanceRange(moved[k]);
    f.movedInstanceIds[static_cast<int>(k)] = moved[k];
    f.movedTriangles[k] = glm::uvec4(range.firstTriangle, range.triangleCount, 0u, 0u);
  }
}

void Renderer::Impl::retraceDirty(const FrameCamera& camera, const FrameShape& shape, std::uint64_t dirty,
                                  std::uint64_t perBatch, const RenderSettings& settings, StageTimes& stageMs,
                                  const std::function<void(double)>& progress) {
  if (dirty == 0) return;
  FrameBlock& f = frameBlock();
  f.refine = reuse.dirtyList.address();
  f.refineInfo = glm::uvec4(0u, FrameReuseState::kListFirst, 0u, 0u);
  const std::uint32_t spp = settings.spp;
  tracePaths(camera, shape, spp, dirty * spp, std::min(perBatch, dirty * spp), TracedTargets::Dirty, settings, stageMs,
             progress);
  f.refine = 0;
  f.refineInfo = glm::uvec4(0u);
}

void Renderer::Impl::runMarkingPass(std::uint64_t targets, bool resetAccumulation, const std::uint32_t* list,
                                    const DeviceBuffer& masks, StageTimes& stageMs,
                                    std::span<const FrameReuseState::SecondaryQueue> secondary,
                                    const ComputePipeline* accumulatedCandidates) {
  // Specialisation: RESET_ACCUMULATION, then MODE (mark_dirty.comp); RESET_ACCUMULATION only when set, so that a
  // single frame's partial re-render keeps the pipeline it always had.
  auto markPipeline = [&](std::uint32_t mode) -> const ComputePipeline& {
    if (mode == 0 && !resetAccumulation) return pipeline(ShaderId::MarkDirty);
    return pipeline(ShaderId::MarkDirty, {resetAccumulation ? 1u : 0u, mode});
  };
  // The masks and the bounce cache are viewed for this pass only: the accumulation's masks and a growing bounce cache
  // may go away while the views stay in the set.
  const bool primaryCached = frameBlock().primaryHits != 0;
  bindReuseTexels(masks, primaryCached, !secondary.empty());
  struct Unbind {
    Impl& impl;
    bool primaryCached, bouncesLinked;
    ~Unbind() {
      try {
        impl.bindReuseTexels(impl.reuseTexelDummy, primaryCached, bouncesLinked);
      } catch (const std::exception&) {  // (unwinding from the pass's own error: that one is reported)
      }
    }
  } unbind{*this, primaryCached, !resetAccumulation && framePlan.bounceLinks};  // a partial re-render reads the links
  beginCommands();
  PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
  for (const FrameReuseState::SecondaryQueue& q : secondary) {  // first: they mark their targets' words 0-1
    rec.dispatch(markPipeline(kMarkSecondaryEntries), passConstants(q.batchFirst, q.count, q.depth, q.base),
                 groupsFor(q.count), Stage::Mark);
  }
  for (std::uint64_t first = 0; first < targets; first += kMarkTargetsPerDispatch) {
    const std::uint64_t n = std::min(kMarkTargetsPerDispatch, targets - first);
    rec.dispatch(
        markPipeline(kMarkTargets),
        passConstants(static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(targets), 0, 0),
        groupsFor((n + gpu_shared::HT_MARK_TARGETS_PER_INVOCATION - 1) / gpu_shared::HT_MARK_TARGETS_PER_INVOCATION),
        Stage::Mark);
  }
  submitAndWait();
  rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
  // The candidates' count sizes the exact pass: read here rather than through an indirect dispatch, which could not
  // be cut into slices of at most 65,535 workgroups (up to one candidate per target: 147,000 groups on a Portrait).
  const std::uint32_t candidates = list[3];
  if (candidates == 0) return;
  beginCommands();
  PassRecorder exact(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
  // mark_accumulated.comp tests one candidate per invocation (its samples' rays are generated again), mark_dirty.comp
  // HT_MARK_TARGETS_PER_INVOCATION (cached rays: lavapipe's cost per invocation dominates).
  const ComputePipeline& test = accumulatedCandidates ? *accumulatedCandidates : markPipeline(kMarkCandidates);
  const std::uint32_t perInvocation = accumulatedCandidates ? 1u : gpu_shared::HT_MARK_TARGETS_PER_INVOCATION;
  for (std::uint32_t first = 0; first < candidates; first += kMarkTargetsPerDispatch) {
    const std::uint64_t n = std::min<std::uint64_t>(kMarkTargetsPerDispatch, candidates - first);
    exact.dispatch(test, passConstants(first, candidates, 0, 0), groupsFor((n + perInvocation - 1) / perInvocation),
                   Stage::Mark);
  }
  submitAndWait();
  exact.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
}

void Renderer::Impl::recordDirtyInterleave(PassRecorder& rec, const FrameShape& shape) {
  // The output image holds the frame this one re-renders in part: the same reuse key (shape, camera, settings) and
  // no frame between them, or the plan would not be a partial re-render.
  const std::uint32_t dirty = static_cast<const std::uint32_t*>(reuse.dirtyList.mapped())[2];
  FrameBlock& f = frameBlock();
  f.refine = reuse.dirtyList.address();
  f.refineInfo = glm::uvec4(0u, FrameReuseState::kListFirst, 0u, 0u);
  const ComputePipeline& listed = pipeline(ShaderId::Interleave, {shape.model, 1u});
  for (std::uint64_t first = 0; first < dirty; first += kMarkTargetsPerDispatch) {
    const std::uint64_t n = std::min<std::uint64_t>(kMarkTargetsPerDispatch, dirty - first);
    rec.dispatch(listed, passConstants(static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(n), 0, 0),
                 groupsFor(n), Stage::Interleave);
  }
}

void Renderer::Impl::copySecondary(std::uint32_t depth, std::uint32_t batchFirst, bool load) {
  // The queue's size is known here (the frame that fills the cache copied it to secondaryCounts before this): only
  // its entries are copied, not the batch's worth (the later depths' queues are a fraction of the batch, and
  // lavapipe copies at memcpy speed on one thread: 4 x 26 MB took about 15 ms on the HPO wall).
  const std::uint32_t count = reuse.secondaryCount(batchFirst, depth);
  if (count == 0) return;
  const std::optional<std::uint32_t> base =
      load ? reuse.secondaryBase(batchFirst, depth) : reuse.reserveSecondary(batchFirst, depth, count);
  if (!base) return;  // the cache overflowed: the frame keeps no state (FrameReuseState::frameDone)
  const FrameReuseState::SecondaryRegion r = reuse.secondaryRegion();
  const std::uint32_t q = depth % 2;
  const struct {
    const DeviceBuffer& work;
    VkDeviceSize cacheOffset, entryBytes;
  } parts[] = {{work.rays[q], r.rays, sizeof(gpu_shared::HtRay)},
               {work.queuePath[q], r.paths, sizeof(std::uint32_t)},
               {work.hits, r.hits, sizeof(gpu_shared::HtHit)}};
  for (const auto& part : parts) {
    const VkDeviceSize at = part.cacheOffset + VkDeviceSize{*base} * part.entryBytes;
    const VkDeviceSize bytes = VkDeviceSize{count} * part.entryBytes;
    if (load) {
      recordComputeCopy(cmd, reuse.secondaryCache, at, part.work, 0, bytes);
    } else {
      recordComputeCopy(cmd, part.work, 0, reuse.secondaryCache, at, bytes);
    }
  }
}

void Renderer::Impl::setBounceLinks(std::uint32_t depth, std::uint32_t batchFirst) {
  FrameBlock& f = frameBlock();
  if (reuse.secondaryOverflowed()) {  // the frame keeps no state: its links would point past the cache
    f.bounceFirst = f.bounceNext = 0;
    return;
  }
  f.bounceNext = reuse.secondaryCache.address() + reuse.secondaryRegion().nexts;  // the cache may have grown
  f.bounceLinks =
      glm::uvec4(depth > 0 ? reuse.secondaryBase(batchFirst, depth) : 0u, reuse.nextSecondaryEntry(), 0u, 0u);
}

void Renderer::setBounceCacheBudget(std::uint64_t bytes) { impl_->reuse.setSecondaryBudget(bytes); }
void Renderer::setMovedInstanceWalks(bool on) { impl_->movedInstanceWalks = on; }
void Renderer::setBounceHitReuse(bool on) { impl_->bounceHitReuse = on; }

Renderer::ReuseSnapshot Renderer::reuseSnapshot() const {
  ReuseSnapshot snap;
  const FrameReuseState& reuse = impl_->reuse;
  snap.grid = reuse.grid();
  if (!reuse.masksValid()) return snap;
  snap.segmentMasks.resize(reuse.maskedTargets() * kMaskWords);
  reuse.segmentMasks.download(snap.segmentMasks.data(), snap.segmentMasks.size() * sizeof(std::uint32_t));
  const ReusePlan& plan = impl_->framePlan;
  snap.movedCells[0] = plan.gridCells[0];
  snap.movedCells[1] = plan.gridCells[1];
  snap.movedLo = plan.movedLo;
  snap.movedHi = plan.movedHi;
  snap.movedBalls[0] = plan.movedBalls[0];
  snap.movedBalls[1] = plan.movedBalls[1];
  if (plan.primaryCached) {
    snap.primaryHits.resize(reuse.primaryHits.size() / sizeof(gpu_shared::HtHit));
    reuse.primaryHits.download(snap.primaryHits.data(), reuse.primaryHits.size());
    snap.primaryRays.resize(reuse.primaryRays.size() / sizeof(gpu_shared::HtRay));
    reuse.primaryRays.download(snap.primaryRays.data(), reuse.primaryRays.size());
  }
  const std::vector<FrameReuseState::SecondaryQueue> queues =
      reuse.secondaryMarkable() ? reuse.secondaryQueues() : std::vector<FrameReuseState::SecondaryQueue>{};
  if (!queues.empty()) {
    std::vector<std::byte> cache(reuse.secondaryCache.size());
    reuse.secondaryCache.download(cache.data(), cache.size());
    const std::uint64_t spp = reuse.cachedPaths() / std::max<std::uint64_t>(reuse.maskedTargets(), 1);
    const FrameReuseState::SecondaryRegion r = reuse.secondaryRegion();
    for (const FrameReuseState::SecondaryQueue& q : queues) {
      for (std::uint64_t e = q.base; e < std::uint64_t{q.base} + q.count; ++e) {
        SecondarySegment s{};
        std::uint32_t path = 0;
        std::memcpy(&s.ray, cache.data() + r.rays + e * sizeof(gpu_shared::HtRay), sizeof(s.ray));
        std::memcpy(&path, cache.data() + r.paths + e * sizeof(std::uint32_t), sizeof(path));
        std::memcpy(&s.hit, cache.data() + r.hits + e * sizeof(gpu_shared::HtHit), sizeof(s.hit));
        s.target = static_cast<std::uint32_t>((q.batchFirst + path) / spp);
        snap.secondarySegments.push_back(s);
      }
    }
  }
  snap.secondaryExact = plan.secondaryExact;
  const auto* list = static_cast<const std::uint32_t*>(reuse.dirtyList.mapped());
  if (list && impl_->framePlan.mode == FrameReuse::PartialRetrace) {
    snap.dirtyTargets.assign(list + FrameReuseState::kListFirst, list + FrameReuseState::kListFirst + list[2]);
  }
  return snap;
}

}  // namespace ht::gpu
