// frame_reuse.h - what a Renderer keeps of the last frame of one view for the edits that follow (docs/REUSE.md §3,
// §4): the primary rays and hits of the frame's samples (a light edit re-shades them and skips raygen and the
// primary trace) and, per target, the world-grid cells its path segments met (a node move re-traces only the
// targets whose cells meet the moved node's old or new bounds). Internal to gpu/.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/bounds3.h"
#include "gpu/device_buffer.h"
#include "gpu/renderer.h"
#include "gpu/segment_cells.h"
#include "gpu/wavefront_types.h"

namespace ht::gpu {

// Device memory the primary-hit cache may take (48 B per path: the ray and its hit). Frames with more paths render
// without the cache (a light edit then costs a full frame).
inline constexpr std::uint64_t kPrimaryHitCacheBudget = 1ull << 30;
inline constexpr std::uint64_t kPrimaryHitBytesPerPath = sizeof(gpu_shared::HtRay) + sizeof(gpu_shared::HtHit);
// The closest-hit queues of the later depths (mirror and glass bounces), which do not depend on the lights either:
// per entry a ray, its path index, its hit and the entry of its path's next bounce (56 B); the same kind of budget. The
// queues are packed one after the other, so the cache holds the entries the frame traced, not a batch's worth per
// depth: a full Portrait frame of the showcase (9.4 M paths, 4 bounce depths) would need 1.96 GB for the worst case and
// holds 2.08 M entries (108 MB).
inline constexpr std::uint64_t kSecondaryHitCacheBudget = 1ull << 30;
inline constexpr std::uint64_t kSecondaryBytesPerPath =
    sizeof(gpu_shared::HtRay) + 2 * sizeof(std::uint32_t) + sizeof(gpu_shared::HtHit);

// The identity of a frame for reuse: its FrameBlock as filled for the base pass (camera, shape, spp, seed, filter,
// depth, light count, region) and the settings outside that block. Two frames with equal keys trace the same
// primary rays.
struct ReuseKey {
  std::vector<std::byte> bytes;
  bool operator==(const ReuseKey&) const = default;
};

// No balls around moved geometry (ReusePlan::movedBalls): the marking pass tests the moved bounds alone.
inline const std::array<glm::vec4, 2> kNoBalls = {kNoBall, kNoBall};

// How the next frame is rendered, decided from the key and the edits since the last recorded frame.
struct ReusePlan {
  FrameReuse mode = FrameReuse::None;
  bool recordHits = false;       // copy the primary rays and hits into the cache (base pass)
  bool recordSecondary = false;  // copy the queues and hits of depths >= 1 into the secondary cache (base pass;
                                 // also in a CachedPrimaryHits frame after a partial re-render left them stale)
  bool loadSecondary = false;    // CachedPrimaryHits: load those too, skipping every closest-hit trace
  bool recordSegments = false;   // record the per-target segment cells (every pass of the frame)
  bool primaryCached = false;    // the cache holds every path's primary ray and hit once the frame ran: primary
                                 // segments stay out of the masks and the marking pass tests them exactly
  // PartialRetrace: the secondary cache holds the segments of depths >= 1 of every target whose mask words 0-1 are
  // zero (recorded by a full frame of this view and still current for every target not re-traced since); the
  // marking pass tests those entries and their shadow rays exactly (mark_dirty.comp MARK_SECONDARY_ENTRIES).
  bool secondaryExact = false;
  // PartialRetrace with secondaryExact: the bounce links (FrameReuseState::bounceFirst) hold, for every path not
  // re-traced since the cache was filled, the entries of its bounce rays, whose hits a bounce ray of the partial
  // re-render takes when it is the cached ray bit for bit and its cached segment avoids the padded moved bounds.
  bool bounceLinks = false;
  // PartialRetrace: the cells of the moved bounds (lo, hi words) and those bounds padded by HT_GRID_PAD cells.
  std::uint32_t gridCells[2] = {0, 0};
  glm::vec3 movedLo{0.0f}, movedHi{0.0f};
  // ... and the balls around the moved geometry before and after its move (w < 0: none; FrameBlock::movedBalls).
  std::array<glm::vec4, 2> movedBalls = kNoBalls;
  // PartialRetrace: the two-level BVH's instances moved since the last frame, when every move named them and they
  // are at most HT_MAX_WALKED_INSTANCES (else empty): traced rays walk from their cached hits
  // (FrameBlock::movedInstanceIds).
  std::vector<std::uint32_t> walkedInstances;
  // The shadow-occlusion cache (shadowOcclusion; docs/REUSE.md §3): a word per depth and path, bits 0-15 the
  // occlusion of the path's shadow ray to light l at that depth, bits 16-31 whether that ray was traced since its
  // hit was found. `occlusionDepths`: the depths whose words the frame writes (shade.comp OCCLUSION; 0: none).
  // CachedPrimaryHits: `occlusionKeptDepths` of them still hold for the lights in `keptLightRays`, whose shadow rays
  // are those recorded; their slots take the recorded occlusion and are not traced.
  std::uint32_t occlusionDepths = 0, occlusionKeptDepths = 0, keptLightRays = 0;
};

class FrameReuseState {
 public:
  // The world grid of the segment masks, over `sceneBounds` (fixed at load: later moves do not change it).
  FrameReuseState(VulkanContext::Impl& vk, const Bounds3& sceneBounds);

  const gpu_shared::SegmentGrid& grid() const { return grid_; }
  bool masksValid() const { return masksValid_; }
  std::uint64_t maskedTargets() const { return maskedTargets_; }  // targets of the frame the masks belong to

  // Edits between frames. Light values: the cached hits stay valid, the segment masks too (lights move no
  // geometry; a reused frame records its shadow segments again). A node moved from `oldBounds` to `newBounds`: the
  // masks and hits stay valid for the marking pass (the partial re-render writes its targets' new hits). Anything
  // else (replaceScene without bounds): nothing is kept.
  // `raysChanged`: bit l = light l's shadow rays changed (GpuScene::updateLights); the others' recorded occlusion
  // stays.
  void lightsEdited(std::uint32_t raysChanged) {
    lightsEdited_ = true;
    lightRaysChanged_ |= raysChanged;
  }
  // `instances`: the two-level BVH's instances the move changed (Renderer::moveNodes), none when not known;
  // `balls`: around the moved geometry before and after (MovedBounds), none when not known.
  void geometryMoved(const Bounds3& oldBounds, const Bounds3& newBounds,
                     std::optional<std::span<const std::uint32_t>> instances = std::nullopt,
                     std::optional<std::array<glm::vec4, 2>> balls = std::nullopt);
  void invalidate();

  // The plan of a frame with `key` of `paths` paths and `targets` targets; `wanted` = RenderSettings::reuse,
  // `reusable` = the frame is one chunk without adaptive refinement (the only frames whose state is kept). Until
  // frameDone, nothing is valid (a frame that throws leaves no half-written state behind).
  // `secondaryDepths`: the depths after the primary one the frame traces (0 without mirrors and glass).
  // `perBatch`: paths per batch of the frame (the secondary cache's queue sizes are kept per batch and depth).
  ReusePlan plan(const ReuseKey& key, bool wanted, bool reusable, std::uint64_t paths, std::uint64_t targets,
                 std::uint32_t secondaryDepths, std::uint64_t perBatch);
  // After the frame planned last finished: what it recorded is now the state edits are measured against.
  void frameDone(const ReuseKey& key, const ReusePlan& plan);

  // Sized by plan(): primary rays and hits of every path of the frame (path order), segment masks (kMaskWords per
  // target), and the dirty-target list (header: the count in word 2; entries from kListFirst).
  // The secondary cache holds secondaryEntries() entries: their rays, then their hits, then their path indices
  // (secondaryRegion). The queue of each batch and depth >= 1 takes the next `count` entries (secondaryBase), in
  // the order the frame traced them; a frame whose queues overflow the cache keeps no state (frameDone).
  // secondaryCounts: the entries of each batch's queue of each depth (batch * (secondaryDepths + 1) + depth), copied
  // from the queue counters by the frame that fills the secondary cache; host visible.
  // shadowOcclusion: with the primary hits, a word per path and depth (depth-major: word depth * paths + path), for
  // depth 0 and, with the secondary cache, every later depth (ReusePlan::occlusionDepths).
  // bounceFirst: with the secondary cache, per frame path the entry of its depth-1 ray (HT_NO_BOUNCE: none), and
  // the cache's `nexts` the entry of the next depth's ray of the entry's path, both written by the frame that fills
  // the cache (shade.comp LINK_BOUNCES). A partial re-render sets the first link of every path it traces to
  // HT_NO_BOUNCE once the path is done (resolve.comp CLEAR_BOUNCE_LINKS): its entries may no longer be current.
  DeviceBuffer primaryRays, primaryHits, segmentMasks, dirtyList, secondaryCache, secondaryCounts, shadowOcclusion,
      bounceFirst;
  struct SecondaryRegion {
    VkDeviceSize rays, paths, hits, nexts;  // byte offsets of entry 0's ray, path index, hit and next link
  };
  SecondaryRegion secondaryRegion() const;
  std::uint64_t secondaryEntries() const { return secondaryEntries_; }
  void setSecondaryBudget(std::uint64_t bytes) { secondaryBudget_ = bytes; }
  VkDeviceSize secondaryCountOffset(std::uint64_t batchFirst, std::uint32_t depth) const;
  // While a frame fills the cache: the first entry of the queue of (batch, depth), `count` entries, taken from the
  // cache's free space; none when they do not fit (the cache overflowed: the frame then keeps no state).
  std::optional<std::uint32_t> reserveSecondary(std::uint64_t batchFirst, std::uint32_t depth, std::uint32_t count);
  std::uint32_t secondaryBase(std::uint64_t batchFirst, std::uint32_t depth) const;
  // The entry the next queue reserved will start at (the bounce links of the queue shaded before it point there).
  std::uint32_t nextSecondaryEntry() const { return static_cast<std::uint32_t>(secondaryUsed_); }
  bool secondaryOverflowed() const { return secondaryOverflow_; }
  // The cached queues of depths >= 1 (what the frame that filled the cache traced), for the marking pass of a frame
  // whose plan says secondaryExact; between frames, while secondaryMarkable().
  struct SecondaryQueue {
    std::uint32_t batchFirst, depth, count;
    std::uint32_t base;  // its first entry in the cache
  };
  std::vector<SecondaryQueue> secondaryQueues() const;
  std::uint32_t secondaryCount(std::uint64_t batchFirst, std::uint32_t depth) const;  // entries of one cached queue
  std::uint64_t cachedPaths() const { return cachedPaths_; }
  bool secondaryMarkable() const { return secondaryMarkable_; }
  // List header: the count of dirty targets (word 2) and of candidates for the exact tests (3; their entries from
  // FrameBlock::moved.z), the other words zero.
  static constexpr std::uint32_t kListFirst = 16;
  // Clears the header of a marking pass's list and writes the pass's inputs into the frame block (FrameBlock::movedLo,
  // movedHi, moved): the moved cells, the padded moved bounds, where the candidates' entries start (0: no exact
  // tests) and the bounce cache's entries (0: none tested).
  static void writeMarkingInputs(std::uint32_t* list, gpu_shared::FrameBlock& frame, const std::uint32_t cells[2],
                                 const glm::vec3& paddedLo, const glm::vec3& paddedHi, std::uint32_t candidatesFirst,
                                 std::uint32_t bounceEntries, const std::array<glm::vec4, 2>& balls);

 private:
  void ensure(DeviceBuffer& buffer, std::uint64_t bytes, MemoryPlace place);
  // The most entries a secondary cache may hold within its texel view (HT_BINDING_REUSE_BOUNCES).
  std::uint64_t secondaryTexelLimit() const;
  // Moves the secondary cache to a buffer of `entries` entries, with the entries used so far (between submits).
  void growSecondary(std::uint64_t entries);
  VulkanContext::Impl& vk_;
  gpu_shared::SegmentGrid grid_{};
  ReuseKey key_;
  bool hitsValid_ = false, masksValid_ = false, secondaryValid_ = false;
  std::uint64_t cachedPaths_ = 0;
  bool secondaryMarkable_ = false;  // the invariant of ReusePlan::secondaryExact holds
  std::uint64_t countsPerBatch_ = 0;
  std::uint32_t countsDepths_ = 0;
  std::uint64_t secondaryBudget_ = kSecondaryHitCacheBudget;
  std::uint64_t secondaryEntries_ = 0;         // the secondary cache's capacity
  std::uint64_t secondaryUsed_ = 0;            // entries its queues took so far
  bool secondaryOverflow_ = false;             // a queue of the frame filling it did not fit
  bool secondaryTooLarge_ = false;             // ... so this view's frames record without the cache
  std::vector<std::uint32_t> secondaryBases_;  // per (batch, depth), as secondaryCounts
  std::uint64_t maskedTargets_ = 0;
  bool lightsEdited_ = false, moved_ = false;
  std::uint32_t lightRaysChanged_ = 0;  // since the last frame
  Bounds3 movedBounds_;
  // Balls around the moved geometry, before and after (MovedBounds): kept when the only move since the last frame
  // gave both, else none (w < 0).
  std::array<glm::vec4, 2> movedBalls_ = kNoBalls;
  std::vector<std::uint32_t> movedInstances_;  // since the last frame, ascending
  bool movedInstancesKnown_ = true;            // every move since the last frame named its instances
};

// Words of a target's segment mask: the cells of its segments but the cached primary ones and their shadow rays
// (0-1), the cells of its cached primary segments and their shadow rays (2-3; zero without the cache),
// record_segments.comp.
inline constexpr std::uint32_t kMaskWords = 4;
// What a progressive accumulation records after the masks, in blocks of a word per target: the reach of each
// target's primary segments, and its nearest and farthest primary hit (common.glsl accum_reach_word).
inline constexpr std::uint32_t kAccumulationBoundWords = 3;

// The moved bounds `moved` padded by HT_GRID_PAD cells of `grid`, what the marking passes test segments against (an
// empty box: one no segment meets).
Bounds3 paddedMovedBounds(const Bounds3& moved, const gpu_shared::SegmentGrid& grid);

// Bytes of a secondary cache of `entries` entries (its four arrays, each on a 16-byte boundary: at most
// kSecondaryBytesPerPath per entry + 32).
VkDeviceSize secondaryBytes(std::uint64_t entries);

// CPU reference of an accumulation's marking pass (mark_dirty.comp MARK_TARGETS with RESET_ACCUMULATION, then
// mark_accumulated.comp): the targets (ascending) whose mask words 0-1 share a cell with `cells`, or whose words
// 2-3 do and one of whose first samples[t] primary rays (`rays`: raysPerTarget per target, sample k of target t at
// t * raysPerTarget + k) meets `padded` up to the target's reach, or a shadow ray to one of `lights` from the box of
// their points between its nearest and farthest hit does (ht_box_shadow_meets_box); a target of more than
// HT_MARK_MAX_SAMPLES samples restarts untested. `masks`: Accumulator::downloadMasks().
std::vector<std::uint32_t> markAccumulatedTargets(std::span<const std::uint32_t> masks, const std::uint32_t cells[2],
                                                  const Bounds3& padded, std::span<const std::uint32_t> samples,
                                                  std::span<const gpu_shared::HtRay> rays, std::uint32_t raysPerTarget,
                                                  std::span<const gpu_shared::GpuLight> lights);

// CPU reference of mark_dirty.comp: the targets (ascending) whose masks (kMaskWords per target) share a cell with
// `plan.gridCells` in words 0-1; or whose words 0-1 are zero and one of whose `secondary` segments (empty unless
// plan.secondaryExact), or a shadow ray from its hit, meets the box [plan.movedLo, plan.movedHi]; or, with cached
// primary rays and hits (`spp` per target; empty: none), whose words 2-3 share a cell with it and one of whose primary
// segments, or a shadow ray from its hit to one of the scene's `lights` (ht_shadow_meets_box), meets that box.
std::vector<std::uint32_t> markDirtyTargets(std::span<const std::uint32_t> masks, const ReusePlan& plan,
                                            std::span<const gpu_shared::HtRay> primaryRays,
                                            std::span<const gpu_shared::HtHit> primaryHits, std::uint32_t spp,
                                            std::span<const gpu_shared::GpuLight> lights,
                                            std::span<const SecondarySegment> secondary);

// Records a buffer-to-buffer copy between compute passes: waits for the passes before it and makes the copy
// visible (and its source free to overwrite) to the passes after it.
void recordComputeCopy(VkCommandBuffer cmd, const DeviceBuffer& src, VkDeviceSize srcOffset, const DeviceBuffer& dst,
                       VkDeviceSize dstOffset, VkDeviceSize bytes);

}  // namespace ht::gpu
