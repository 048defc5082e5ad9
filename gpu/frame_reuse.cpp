// frame_reuse.cpp - see frame_reuse.h.
#include "gpu/frame_reuse.h"

#include <algorithm>
#include <cstring>

namespace ht::gpu {

FrameReuseState::FrameReuseState(VulkanContext::Impl& vk, const Bounds3& sceneBounds) : vk_(vk) {
  glm::vec3 lo(0.0f), extent(1.0f);
  if (!sceneBounds.empty()) {
    lo = sceneBounds.lo;
    extent = sceneBounds.extent();
  }
  // A flat scene (zero extent along an axis) still gets cells of a finite size there.
  const float largest = std::max({extent.x, extent.y, extent.z, 1e-6f});
  extent = glm::max(extent, glm::vec3(largest * 1e-3f));
  grid_.origin = glm::vec4(lo, 0.0f);
  grid_.scale = glm::vec4(static_cast<float>(gpu_shared::HT_GRID_CELLS) / extent, 0.0f);
}

void FrameReuseState::geometryMoved(const Bounds3& oldBounds, const Bounds3& newBounds,
                                    std::optional<std::span<const std::uint32_t>> instances,
                                    std::optional<std::array<glm::vec4, 2>> balls) {
  const bool firstMove = !moved_;  // since the last frame (invalidate)
  moved_ = true;
  if (instances) {
    movedInstances_.insert(movedInstances_.end(), instances->begin(), instances->end());
    std::sort(movedInstances_.begin(), movedInstances_.end());
    movedInstances_.erase(std::unique(movedInstances_.begin(), movedInstances_.end()), movedInstances_.end());
  } else {
    movedInstancesKnown_ = false;
  }
  for (const Bounds3& b : {oldBounds, newBounds}) {
    if (b.empty()) continue;
    movedBounds_.extend(b.lo);
    movedBounds_.extend(b.hi);
  }
  const bool ballsGiven = balls && (*balls)[0].w >= 0.0f && (*balls)[1].w >= 0.0f;
  movedBalls_ = firstMove && ballsGiven ? *balls : kNoBalls;
}

void FrameReuseState::invalidate() {
  hitsValid_ = masksValid_ = secondaryValid_ = secondaryMarkable_ = false;
  lightsEdited_ = moved_ = false;
  lightRaysChanged_ = 0;
  movedBounds_ = Bounds3{};
  movedBalls_ = kNoBalls;
  movedInstances_.clear();
  movedInstancesKnown_ = true;
}

void FrameReuseState::ensure(DeviceBuffer& buffer, std::uint64_t bytes, MemoryPlace place) {
  if (buffer.size() < bytes) buffer = DeviceBuffer(vk_, bytes, place);
}

ReusePlan FrameReuseState::plan(const ReuseKey& key, bool wanted, bool reusable, std::uint64_t paths,
                                std::uint64_t targets, std::uint32_t secondaryDepths, std::uint64_t perBatch) {
  ReusePlan p;
  // The marking pass reads the masks through a texel view of one texel per target (HT_BINDING_REUSE_MASKS).
  const std::uint64_t maxTexels = vk_.info.maxTexelBufferElements;
  if (!wanted || !reusable || targets > maxTexels) {
    invalidate();
    if (!wanted) {  // free the memory
      for (DeviceBuffer* b : {&primaryRays, &primaryHits, &segmentMasks, &dirtyList, &secondaryCache, &secondaryCounts,
                              &shadowOcclusion, &bounceFirst}) {
        *b = DeviceBuffer();
      }
    }
    return p;
  }
  // Fixed by the key (paths): every frame of one view caches its primary hits or none does.
  // Its texel view holds 2 texels per path's ray (HT_BINDING_REUSE_PRIMARY_RAYS).
  p.primaryCached = paths * kPrimaryHitBytesPerPath <= kPrimaryHitCacheBudget && 2 * paths <= maxTexels;
  const bool sameView = key == key_;
  if (sameView && !moved_ && hitsValid_) {
    p.mode = FrameReuse::CachedPrimaryHits;  // light values edited, or nothing at all
  } else if (sameView && moved_ && !lightsEdited_ && masksValid_ && (hitsValid_ || !p.primaryCached)) {
    p.mode = FrameReuse::PartialRetrace;
    if (!movedBounds_.empty()) {  // else no cells, and an empty box no segment meets
      const gpu_shared::uvec2 cells = gpu_shared::ht_grid_bounds_mask(movedBounds_.lo, movedBounds_.hi, grid_);
      p.gridCells[0] = cells.x;
      p.gridCells[1] = cells.y;
    }
    const Bounds3 padded = paddedMovedBounds(movedBounds_, grid_);
    p.movedLo = padded.lo;
    p.movedHi = padded.hi;
    p.movedBalls = movedBalls_;
    if (movedInstancesKnown_ && movedInstances_.size() <= gpu_shared::HT_MAX_WALKED_INSTANCES)
      p.walkedInstances = movedInstances_;
  }
  p.recordHits = p.mode == FrameReuse::None && p.primaryCached;
  // The secondary cache takes at most the budget; whether the frame's bounce queues fit is known as they are traced.
  // It starts at a quarter of the paths (the showcase's bounces take 5-7 % of paths x depths) and grows by doubling.
  // Its texel view (HT_BINDING_REUSE_BOUNCES) covers it whole: 16-byte texels.
  const std::uint64_t entries =
      std::min({paths * secondaryDepths, secondaryBudget_ / kSecondaryBytesPerPath, secondaryTexelLimit()});
  if (!sameView) secondaryTooLarge_ = false;
  const bool secondaryFits = p.primaryCached && secondaryDepths > 0 && entries > 0 && !secondaryTooLarge_;
  p.recordSecondary =
      secondaryFits && (p.mode == FrameReuse::None || (p.mode == FrameReuse::CachedPrimaryHits && !secondaryValid_));
  p.loadSecondary = p.mode == FrameReuse::CachedPrimaryHits && secondaryFits && secondaryValid_;
  p.secondaryExact = p.mode == FrameReuse::PartialRetrace && secondaryMarkable_ && cachedPaths_ == paths;
  // Every frame that makes secondaryMarkable_ true wrote the links (recordSecondary) or kept those of the frame that
  // did (loadSecondary, or a partial re-render, which clears its paths' first links).
  p.bounceLinks = p.secondaryExact && bounceFirst.size() >= paths * sizeof(std::uint32_t);
  if (p.recordSecondary) {
    const std::uint64_t held = secondaryCache.size() / kSecondaryBytesPerPath;  // a buffer kept from earlier frames
    secondaryEntries_ = std::min(entries, std::max({paths / 4, std::uint64_t{1024}, held}));
    ensure(secondaryCache, secondaryBytes(secondaryEntries_), MemoryPlace::Device);
    ensure(bounceFirst, paths * sizeof(std::uint32_t), MemoryPlace::Device);
    secondaryUsed_ = 0;
    secondaryOverflow_ = false;
    countsPerBatch_ = perBatch;
    countsDepths_ = secondaryDepths + 1;
    const std::uint64_t batches = (paths + perBatch - 1) / perBatch;
    secondaryBases_.assign(batches * countsDepths_, 0u);
    const std::uint64_t countBytes = batches * countsDepths_ * sizeof(std::uint32_t);
    ensure(secondaryCounts, countBytes, MemoryPlace::HostReadback);
    std::memset(secondaryCounts.mapped(), 0, countBytes);  // depths a batch never reached hold no entries
  }
  cachedPaths_ = paths;
  p.recordSegments = true;
  if (p.primaryCached) {
    // Occlusion words for every depth where the hits of every depth are cached, else for depth 0. A partial
    // re-render writes depth 0's for its listed paths and leaves the later depths' stale, as it leaves their hits:
    // the words of depths >= 1 hold while the secondary cache does (loadSecondary), which every frame that writes
    // that cache fills with its words.
    const std::uint32_t depths = secondaryFits ? secondaryDepths + 1 : 1;
    p.occlusionDepths = p.mode == FrameReuse::PartialRetrace ? 1 : depths;
    if (p.mode == FrameReuse::CachedPrimaryHits) {
      p.occlusionKeptDepths = p.loadSecondary ? depths : 1;
      p.keptLightRays = ~lightRaysChanged_ & ((1u << gpu_shared::HT_MAX_LIGHTS) - 1u);
    }
    ensure(primaryRays, paths * sizeof(gpu_shared::HtRay), MemoryPlace::Device);
    ensure(primaryHits, paths * sizeof(gpu_shared::HtHit), MemoryPlace::Device);
    ensure(shadowOcclusion, depths * paths * sizeof(std::uint32_t), MemoryPlace::Device);
  }
  ensure(segmentMasks, targets * kMaskWords * sizeof(std::uint32_t), MemoryPlace::Device);
  // The dirty list, then (with the primary cache) the marking pass's candidates for its exact tests.
  ensure(dirtyList, (kListFirst + (p.primaryCached ? 2 : 1) * targets) * sizeof(std::uint32_t),
         MemoryPlace::HostReadback);
  maskedTargets_ = targets;
  invalidate();  // valid again once the frame finished (frameDone)
  return p;
}

void FrameReuseState::frameDone(const ReuseKey& key, const ReusePlan& plan) {
  key_ = key;
  masksValid_ = plan.recordSegments;
  hitsValid_ = plan.primaryCached;
  secondaryValid_ = plan.recordSecondary || plan.loadSecondary;  // a partial re-render leaves them stale
  // ... for its re-traced targets only: those get coarse cells in mask words 0-1, the others' entries stay current.
  secondaryMarkable_ = plan.recordSecondary || plan.loadSecondary || plan.secondaryExact;
  if (plan.recordSecondary && secondaryOverflow_) {
    // Bounce queues that did not fit recorded neither entries nor cells (their segments were meant for the cache):
    // nothing after this frame may reuse it, and the next frame of this view records without the cache.
    invalidate();
    secondaryTooLarge_ = true;
  }
}

VkDeviceSize FrameReuseState::secondaryCountOffset(std::uint64_t batchFirst, std::uint32_t depth) const {
  return ((batchFirst / countsPerBatch_) * countsDepths_ + depth) * sizeof(std::uint32_t);
}

std::uint32_t FrameReuseState::secondaryCount(std::uint64_t batchFirst, std::uint32_t depth) const {
  const auto* counts = static_cast<const std::uint32_t*>(secondaryCounts.mapped());
  if (counts == nullptr || countsPerBatch_ == 0 || depth >= countsDepths_) return 0;
  return counts[secondaryCountOffset(batchFirst, depth) / sizeof(std::uint32_t)];
}

std::vector<FrameReuseState::SecondaryQueue> FrameReuseState::secondaryQueues() const {
  std::vector<SecondaryQueue> queues;
  if (countsPerBatch_ == 0) return queues;
  for (std::uint64_t first = 0; first < cachedPaths_; first += countsPerBatch_) {
    for (std::uint32_t depth = 1; depth < countsDepths_; ++depth) {
      const std::uint32_t count = secondaryCount(first, depth);
      if (count > 0) queues.push_back({static_cast<std::uint32_t>(first), depth, count, secondaryBase(first, depth)});
    }
  }
  return queues;
}

namespace {

// Where a secondary cache of `entries` entries keeps its rays, hits, path indices and next links: in that order, so
// that each array starts at a multiple of 16 B and the marking pass and trace_closest read them through one RGBA32UI
// texel view (HT_BINDING_REUSE_BOUNCES, mark_dirty.comp, reuse_cache.glsl).
FrameReuseState::SecondaryRegion secondaryLayout(std::uint64_t entries) {
  const VkDeviceSize rays = entries * sizeof(gpu_shared::HtRay);
  const VkDeviceSize paths = rays + entries * sizeof(gpu_shared::HtHit);
  return {0, paths, rays, paths + (entries + 3) / 4 * 16};
}

}  // namespace

VkDeviceSize secondaryBytes(std::uint64_t entries) { return secondaryLayout(entries).nexts + (entries + 3) / 4 * 16; }

FrameReuseState::SecondaryRegion FrameReuseState::secondaryRegion() const { return secondaryLayout(secondaryEntries_); }

std::uint64_t FrameReuseState::secondaryTexelLimit() const {
  // secondaryBytes(entries) <= entries * kSecondaryBytesPerPath + 32 must fit the view's 16-byte texels.
  return (std::uint64_t{vk_.info.maxTexelBufferElements} * 16 - 32) / kSecondaryBytesPerPath;
}

void FrameReuseState::growSecondary(std::uint64_t entries) {
  DeviceBuffer grown(vk_, secondaryBytes(entries), MemoryPlace::Device);
  if (secondaryUsed_ > 0) {  // the entries so far, each array to its place in the larger layout
    const SecondaryRegion from = secondaryRegion(), to = secondaryLayout(entries);
    const VkBufferCopy parts[] = {{from.rays, to.rays, secondaryUsed_ * sizeof(gpu_shared::HtRay)},
                                  {from.paths, to.paths, secondaryUsed_ * sizeof(std::uint32_t)},
                                  {from.hits, to.hits, secondaryUsed_ * sizeof(gpu_shared::HtHit)},
                                  {from.nexts, to.nexts, secondaryUsed_ * sizeof(std::uint32_t)}};
    OneShotCommands copy(vk_);
    vkCmdCopyBuffer(copy.cmd(), secondaryCache.handle(), grown.handle(), 4, parts);
    copy.submitAndWait();
  }
  secondaryCache = std::move(grown);
  secondaryEntries_ = entries;
}

std::optional<std::uint32_t> FrameReuseState::reserveSecondary(std::uint64_t batchFirst, std::uint32_t depth,
                                                               std::uint32_t count) {
  const std::uint64_t limit = std::min(secondaryBudget_ / kSecondaryBytesPerPath, secondaryTexelLimit());
  if (secondaryOverflow_ || secondaryUsed_ + count > limit) {
    secondaryOverflow_ = true;
    return std::nullopt;
  }
  if (secondaryUsed_ + count > secondaryEntries_) {
    growSecondary(std::min(limit, std::max(2 * secondaryEntries_, secondaryUsed_ + count)));
  }
  const auto base = static_cast<std::uint32_t>(secondaryUsed_);
  secondaryBases_[secondaryCountOffset(batchFirst, depth) / sizeof(std::uint32_t)] = base;
  secondaryUsed_ += count;
  return base;
}

std::uint32_t FrameReuseState::secondaryBase(std::uint64_t batchFirst, std::uint32_t depth) const {
  const std::size_t at = secondaryCountOffset(batchFirst, depth) / sizeof(std::uint32_t);
  return at < secondaryBases_.size() ? secondaryBases_[at] : 0u;
}

namespace {

// Does a cached primary segment, or a shadow ray from its hit to one of `lights`, meet the padded moved bounds?
bool cachedSegmentsMeetMoved(const gpu_shared::HtRay& r, const gpu_shared::HtHit& h, const ReusePlan& plan,
                             std::span<const gpu_shared::GpuLight> lights) {
  const float tEnd = h.triId != gpu_shared::HT_MISS ? h.t : r.tmax;
  const glm::vec4 ball0 = plan.movedBalls[0], ball1 = plan.movedBalls[1];
  if (gpu_shared::ht_segment_meets_box(r.origin, r.dir, r.tmin, tEnd, plan.movedLo, plan.movedHi) &&
      gpu_shared::ht_segment_meets_balls(r.origin, r.dir, r.tmin, tEnd, ball0, ball1)) {
    return true;
  }
  if (h.triId == gpu_shared::HT_MISS) return false;
  const glm::vec3 p = gpu_shared::ht_cached_hit_point(r.origin, r.dir, tEnd);
  const float pErr = gpu_shared::ht_cached_hit_error(r.origin, r.dir, tEnd);
  for (const gpu_shared::GpuLight& light : lights) {
    const glm::vec3 direction(light.direction);
    if (gpu_shared::ht_shadow_meets_box(p, pErr, light.position, direction, plan.movedLo, plan.movedHi) &&
        gpu_shared::ht_shadow_meets_balls(p, pErr, light.position, direction, ball0, ball1)) {
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<std::uint32_t> markDirtyTargets(std::span<const std::uint32_t> masks, const ReusePlan& plan,
                                            std::span<const gpu_shared::HtRay> primaryRays,
                                            std::span<const gpu_shared::HtHit> primaryHits, std::uint32_t spp,
                                            std::span<const gpu_shared::GpuLight> lights,
                                            std::span<const SecondarySegment> secondary) {
  const std::size_t targets = masks.size() / kMaskWords;
  std::vector<bool> secondaryMeets(targets, false);
  for (const SecondarySegment& s : secondary) {
    if (s.target < targets && !secondaryMeets[s.target]) {
      secondaryMeets[s.target] = cachedSegmentsMeetMoved(s.ray, s.hit, plan, lights);
    }
  }
  std::vector<std::uint32_t> dirty;
  for (std::size_t t = 0; t < targets; ++t) {
    const std::uint32_t* m = masks.data() + t * kMaskWords;
    const bool coarse = (m[0] | m[1]) != 0;
    bool hit = coarse ? ((m[0] & plan.gridCells[0]) | (m[1] & plan.gridCells[1])) != 0 : secondaryMeets[t];
    const bool primaryNear = ((m[2] & plan.gridCells[0]) | (m[3] & plan.gridCells[1])) != 0;
    for (std::uint32_t s = 0; !hit && primaryNear && !primaryHits.empty() && s < spp; ++s) {
      hit = cachedSegmentsMeetMoved(primaryRays[t * spp + s], primaryHits[t * spp + s], plan, lights);
    }
    if (hit) dirty.push_back(static_cast<std::uint32_t>(t));
  }
  return dirty;
}

void FrameReuseState::writeMarkingInputs(std::uint32_t* list, gpu_shared::FrameBlock& frame,
                                         const std::uint32_t cells[2], const glm::vec3& paddedLo,
                                         const glm::vec3& paddedHi, std::uint32_t candidatesFirst,
                                         std::uint32_t bounceEntries, const std::array<glm::vec4, 2>& balls) {
  std::memset(list, 0, kListFirst * sizeof(std::uint32_t));
  frame.movedLo = glm::vec4(paddedLo, 0.0f);
  frame.movedHi = glm::vec4(paddedHi, 0.0f);
  frame.movedBalls[0] = balls[0];
  frame.movedBalls[1] = balls[1];
  frame.moved = glm::uvec4(cells[0], cells[1], candidatesFirst, bounceEntries);
}

Bounds3 paddedMovedBounds(const Bounds3& moved, const gpu_shared::SegmentGrid& grid) {
  if (moved.empty()) return Bounds3{glm::vec3(1.0f), glm::vec3(-1.0f)};
  const glm::vec3 pad = gpu_shared::HT_GRID_PAD / glm::vec3(grid.scale);
  return Bounds3{moved.lo - pad, moved.hi + pad};
}

namespace {

// mark_accumulated.comp's samples_meet_moved for target t of `targets` (words of `masks` as it reads them).
bool accumulatedSamplesMeetMoved(std::span<const std::uint32_t> masks, std::size_t targets, std::size_t t,
                                 const Bounds3& padded, std::uint32_t samples, std::span<const gpu_shared::HtRay> rays,
                                 std::span<const gpu_shared::GpuLight> lights) {
  if (samples > gpu_shared::HT_MARK_MAX_SAMPLES) return true;
  const auto word = [&](std::uint32_t block) { return masks[(kMaskWords + block) * targets + t]; };
  const auto asFloat = [](std::uint32_t bits) {
    float v = 0.0f;
    std::memcpy(&v, &bits, sizeof(v));
    return v;
  };
  const float reach = asFloat(word(0)), near = asFloat(~word(1)), far = asFloat(word(2));
  glm::vec3 pLo(gpu_shared::HT_GRID_T_INFINITY), pHi(-gpu_shared::HT_GRID_T_INFINITY);
  float pErr = 0.0f;
  for (std::uint32_t k = 0; k < samples; ++k) {
    const gpu_shared::HtRay& r = rays[k];
    if (gpu_shared::ht_segment_meets_box(r.origin, r.dir, r.tmin, reach, padded.lo, padded.hi)) return true;
    const glm::vec3 a = gpu_shared::ht_cached_hit_point(r.origin, r.dir, near);
    const glm::vec3 b = gpu_shared::ht_cached_hit_point(r.origin, r.dir, far);
    pLo = glm::min(pLo, glm::min(a, b));
    pHi = glm::max(pHi, glm::max(a, b));
    pErr = std::max(pErr, gpu_shared::ht_cached_hit_error(r.origin, r.dir, far));
  }
  for (const gpu_shared::GpuLight& light : lights) {
    if (word(1) != 0 && gpu_shared::ht_box_shadow_meets_box(pLo, pHi, pErr, light.position, glm::vec3(light.direction),
                                                            padded.lo, padded.hi)) {
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<std::uint32_t> markAccumulatedTargets(std::span<const std::uint32_t> masks, const std::uint32_t cells[2],
                                                  const Bounds3& padded, std::span<const std::uint32_t> samples,
                                                  std::span<const gpu_shared::HtRay> rays, std::uint32_t raysPerTarget,
                                                  std::span<const gpu_shared::GpuLight> lights) {
  const std::size_t targets = masks.size() / (kMaskWords + kAccumulationBoundWords);
  std::vector<std::uint32_t> dirty;
  for (std::size_t t = 0; t < targets; ++t) {
    const std::uint32_t* m = masks.data() + t * kMaskWords;
    bool hit = ((m[0] & cells[0]) | (m[1] & cells[1])) != 0;
    if (!hit && ((m[2] & cells[0]) | (m[3] & cells[1])) != 0) {
      if (samples[t] > raysPerTarget && samples[t] <= gpu_shared::HT_MARK_MAX_SAMPLES) {
        throw GpuError("markAccumulatedTargets: fewer rays than samples");
      }
      hit = accumulatedSamplesMeetMoved(masks, targets, t, padded, samples[t], rays.subspan(t * raysPerTarget), lights);
    }
    if (hit) dirty.push_back(static_cast<std::uint32_t>(t));
  }
  return dirty;
}

void recordComputeCopy(VkCommandBuffer cmd, const DeviceBuffer& src, VkDeviceSize srcOffset, const DeviceBuffer& dst,
                       VkDeviceSize dstOffset, VkDeviceSize bytes) {
  VkMemoryBarrier before{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                         VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before, 0,
                       nullptr, 0, nullptr);
  const VkBufferCopy region{srcOffset, dstOffset, bytes};
  vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &region);
  VkMemoryBarrier after{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &after, 0,
                       nullptr, 0, nullptr);
}

}  // namespace ht::gpu
