// renderer_impl.h - Renderer::Impl, shared by the files of the renderer: renderer.cpp (resources, descriptors,
// the frame block, the public API), wavefront_loop.cpp (the frame loop), refinement_pass.cpp (adaptive refinement)
// and ray_batches.cpp (rays without a frame). Internal to gpu/.
#pragma once
#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gpu/compute_pipeline.h"
#include "gpu/device_buffer.h"
#include "gpu/frame_descriptors.h"
#include "gpu/frame_reuse.h"
#include "gpu/gpu_scene.h"
#include "gpu/pass_recorder.h"
#include "gpu/path_buffers.h"
#include "gpu/pipeline_library.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "gpu/wavefront_types.h"

namespace ht::gpu {

using gpu_shared::FrameBlock;
using gpu_shared::GpuCounters;
using gpu_shared::HT_WORKGROUP_SIZE;
using gpu_shared::PassConstants;

inline constexpr std::uint64_t kWorkMemoryBudget = 512ull << 20;  // per-batch path state
inline constexpr std::uint32_t kMaxPathsPerBatch = 1u << 20;
inline constexpr std::uint32_t kQueryCapacity = 4096;
inline constexpr std::uint32_t kMaxSpp = 4096;
inline constexpr std::uint32_t kMaxDepth = 32;
inline constexpr std::uint64_t kMaxChunkPixels = 8ull
                                                 << 20;  // pixels of all views rendered by one chunk (output buffers)

using StageTimes = std::array<double, static_cast<size_t>(Stage::Count)>;

// Workgroups of HT_WORKGROUP_SIZE invocations covering n.
inline std::uint32_t groupsFor(std::uint64_t n) {
  return static_cast<std::uint32_t>((n + gpu_shared::HT_WORKGROUP_SIZE - 1) / gpu_shared::HT_WORKGROUP_SIZE);
}

// `spec` (a kernel's own constants, ids 0..) with constant `id` set to `value`, the ids between left 0: the
// constants common to several kernels sit at fixed high ids (gpu/shader_interface.h HT_SPEC_*).
std::vector<std::uint32_t> withConstant(std::vector<std::uint32_t> spec, std::uint32_t id, std::uint32_t value);

// Throw GpuError naming the value out of range.
void checkSettings(const RenderSettings& settings);
void checkShape(const FrameShape& shape, std::uint32_t spp);

// Which targets a call of tracePaths traces: every target of the chunk (its base pass), the targets adaptive
// refinement listed, or the dirty targets of a partial re-render (gpu/frame_reuse.h).
enum class TracedTargets { All, Refined, Dirty };

// The rows a chunk renders of each of its views: `first` counted from the bottom (as targets count them), of views
// `viewRows` rows high; the chunk's FrameShape::height is the band's row count (RenderSettings::region).
struct RowBand {
  std::uint32_t first = 0;
  std::uint32_t viewRows = 0;
};

}  // namespace ht::gpu

// What an accumulation's sums belong to, and its device buffers (gpu/accumulator.h).
struct ht::gpu::Accumulator::State {
  // AccumTarget per target of the whole frame, in two planes of 16 B per target: sum and n, halfSum and halfN (the
  // storage texel buffers HT_BINDING_ACCUM_SUMS and _HALVES: 2^27 texels on lavapipe, so one plane holds the targets
  // of an 8K panel's subpixels)
  DeviceBuffer sums, halves;
  DeviceBuffer stats;            // AccumStats, host visible
  std::string key;               // accumulationKey() of the frames summed; "" = nothing summed yet
  std::uint64_t generation = 0;  // the renderer's scene generation the sums belong to
  // Partial restart after node moves (docs/REUSE.md §4 in streams): every frame of the accumulation ORs the grid
  // cells of its samples' segments into `masks` (kMaskWords per target, segment_cells.h, then the bounds of each
  // target's primary segments and hits: common.glsl accum_reach_word); after moves, only the
  // targets whose cells meet the moved bounds start over. Kept only for accumulations of one chunk covering the whole
  // frame (target index == frame-global index); `masksValid` false = the next scene change restarts everything.
  DeviceBuffer masks;
  DeviceBuffer dirty;  // the marking pass's list (header + entries, FrameReuseState::kListFirst), host visible
  bool masksValid = false;
  std::optional<Bounds3> pendingMove;  // set by accumulate(): the next frame resets the targets near these bounds
  // The adaptive policy's list (docs/REUSE.md §2): the targets the last frame sampled, a uint per target, kept for
  // accumulations of one chunk. The next frame selects among these only, since a target left out stays converged
  // (its sums no longer change), and shows only the ones it samples. `listed`: its entries; none = the next frame
  // judges every target (after a restart or a move, or when the frame has several chunks).
  DeviceBuffer list;
  std::optional<std::uint64_t> listed;
  // The renderer's chunk count (Impl::chunksRendered) and subpixel-buffer generation when a show pass of this
  // accumulation last wrote the subpixel buffer: while no other chunk has run since, the buffer still holds the values
  // of the targets a frame does not sample.
  std::uint64_t shownChunk = 0, shownOutputs = 0;
};

namespace ht::gpu {

// The identity of an accumulation: the renderer and its scene version, the camera block and shape, and every
// setting that shapes a sample (not spp: frames of different spp continue one accumulation).
// The scene generation is kept apart (Accumulator::State::generation): after node moves only part of it restarts.
std::string accumulationKey(const void* renderer, const FrameCamera& camera, const RenderSettings& settings);

struct Renderer::Impl {
  VulkanContext::Impl& vk;
  GpuScene scene;
  const PipelineLayout& layout;  // the device's (PipelineLibrary), shared with every Renderer
  FrameDescriptors descriptors;
  bool bvhTexelsCover = true;
  std::uint64_t boundWorkGeneration = 0;
  std::uint64_t boundOutputGeneration = 0;
  DeviceBuffer frame;     // FrameBlock, host visible
  DeviceBuffer counters;  // GpuCounters, host visible
  PathBuffers work;
  OutputBuffers outputs;
  VkQueryPool queryPool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  DeviceBuffer refineBuffer;     // adaptive refinement: per-subgroup counts, staging, target list (refine_select.comp)
  DeviceBuffer rayTableTexels;   // the current ray table (2 texels per entry) or a 1-entry dummy
  DeviceBuffer reuseTexelDummy;  // one texel: the reuse and accumulation views (HT_BINDING_REUSE_*, _ACCUM_*) where
                                 // none is bound
  std::shared_ptr<const RayTable> boundRayTable;  // which table rayTableTexels holds

  bvh::BuildOptions buildOptions;
  BvhStats bvhStats;
  // Bumped by every scene change (sceneChanged): replaceScene, moveNodes, updateLights (accumulation keys). The last
  // changes are logged with the world bounds they moved (none: anything may have changed), so an accumulation can
  // restart only the targets near moved nodes (accumulation_pass.cpp).
  std::uint64_t sceneGeneration = 0;
  struct SceneChange {
    std::uint64_t generation = 0;  // after the change
    std::optional<Bounds3> moved;  // node moves: the union of the moved nodes' bounds before and after
  };
  std::deque<SceneChange> sceneChanges;  // the last kSceneChangeLog changes
  static constexpr std::size_t kSceneChangeLog = 64;
  Accumulator* accumulating = nullptr;        // during accumulate(): the accumulation the chunks add to
  std::uint64_t chunksRendered = 0;           // chunks begun by render(): whose values the subpixel buffer holds
  std::mutex spareMutex;                      // guards spareRgba (Renderer::recycle may come from another thread)
  std::vector<std::vector<float>> spareRgba;  // recycled frame buffers for the next render()s, at most kSpareFrames
  static constexpr std::size_t kSpareFrames = 2;
  FrameReuseState reuse;  // what the next frame of the same view may reuse (RenderSettings::reuse)
  ReusePlan framePlan;    // the plan of the chunk being rendered

  Impl(VulkanContext::Impl& v, GpuScene&& s, const bvh::BuildOptions& o, const Bounds3& sceneBounds);

  ~Impl();

  const ComputePipeline& pipeline(ShaderId id, const std::vector<std::uint32_t>& spec = {}) {
    return vk.pipelines->get(id, spec);
  }

  // Specialisation of raygen: the camera model, then a lenticular panel's Gen3 cell mode and count, so the cell code
  // folds to the panel's own pattern (lenticular_model.h HT_LENTICULAR_CELL_MODE; a CPU driver pays for untaken code),
  // then REFINING for the pass over listed targets.
  static_assert(gpu_shared::HT_SPEC_MODEL == 0, "raygen, resolve and refine_select take the model as constant 0");
  // PROGRESSIVE (constant 4) is appended only when set, so single frames keep their pipelines.
  static std::vector<std::uint32_t> raygenSpec(const FrameCamera& camera, const FrameShape& shape,
                                               bool refining = false, bool progressive = false) {
    const auto* lenticular = std::get_if<gpu_shared::LenticularParams>(&camera);
    std::vector<std::uint32_t> spec{shape.model, 0u, 0u, refining};
    if (lenticular) {
      spec[1] = static_cast<std::uint32_t>(lenticular->flags.x);
      spec[2] = static_cast<std::uint32_t>(lenticular->flags.y);
    }
    if (progressive) spec.push_back(1u);
    return spec;
  }

  // Specialisation of the kernels that continue paths (shade, gather_direct): their own constants, then
  // PRIMARY_DEPTH, true for the dispatches at depth 0 (common.glsl queue_path).
  static std::vector<std::uint32_t> depthSpec(std::vector<std::uint32_t> own, std::uint32_t depth) {
    return withConstant(std::move(own), gpu_shared::HT_SPEC_PRIMARY_DEPTH, depth == 0 ? 1u : 0u);
  }

  // Specialisation of the trace kernels: their own constants, then TEXEL_FETCH and TWO_LEVEL.
  std::vector<std::uint32_t> traceSpec(std::vector<std::uint32_t> own) const {
    const bool twoLevel = scene.layout() == bvh::BvhLayout::TwoLevel;
    return withConstant(withConstant(std::move(own), gpu_shared::HT_SPEC_TEXEL_FETCH, bvhTexelsCover ? 1u : 0u),
                        gpu_shared::HT_SPEC_TWO_LEVEL, twoLevel ? 1u : 0u);
  }

  // Binding HT_BINDING_RAY_TABLE: `table`'s entries (uploaded when the table object changes); without a table the
  // bound one stays, or a dummy entry so the descriptor is valid.
  void bindRayTable(const std::shared_ptr<const RayTable>& table);

  // A new BVH and scene records, built and uploaded before the current ones are released (a failure leaves them);
  // pipelines, work and output buffers stay. Every frame waits for its own work, so nothing in flight reads them.
  void replaceScene(const Scene& s, BvhLayoutPolicy policy);

  // New light values (same count) into the bound light buffer: no BVH build, no descriptor change.
  void updateLights(const Scene& s);
  // Renderer::moveNodes.
  // Returns the two-level BVH's instances it moved.
  std::vector<std::uint32_t> moveNodes(const Scene& s, std::span<const std::uint32_t> nodes,
                                       const std::optional<MovedBounds>& bounds);
  // A new scene generation, logged with the bounds a node move changed (nullopt: a change of any kind).
  void sceneChanged(std::optional<Bounds3> moved);
  // The union of the moved bounds of every change after `generation`; nullopt when one of them was not a move or
  // the log no longer reaches back that far.
  std::optional<Bounds3> movedSince(std::uint64_t generation) const;
  // Replaces the device scene by one built from `bvh` (replaceScene, a layout switch).
  void installScene(const Scene& s, SceneBvh bvh);

  FrameBlock& frameBlock() { return *static_cast<FrameBlock*>(frame.mapped()); }
  GpuCounters& counterBlock() { return *static_cast<GpuCounters*>(counters.mapped()); }

  // Scene records and BVH views: written at construction and again by replaceScene, whose new buffers were created
  // while the bound ones still existed, so their handles differ and every view is rebuilt.
  void bindScene();

  // Per-path state of the current work buffers, plus the frame's outputs.
  void bindState();

  void fillFrameBasics(FrameBlock& f) {
    f.counters = counters.address();
    f.flags = glm::uvec4(scene.hasNormals ? 1u : 0u, scene.hasTexcoords ? 1u : 0u, 0u, 0u);
  }

  PassConstants passConstants(std::uint32_t first, std::uint32_t count, std::uint32_t depth,
                              std::uint32_t queue) const {
    return PassConstants{
        frame.address(), scene.nodes.address(), scene.bvhTriangles.address(), first, count, depth, queue};
  }

  void beginCommands();

  void submitAndWait();

  // Throws GpuError when a ray hit the traversal step limit (its hits could be missing).
  void checkCounters(const char* what);

  // Writes the camera block and the frame-wide values of a chunk of `shape` (height: the band's rows) covering views
  // [viewFirst, +viewCount) and rows `band` of each.
  void fillFrame(const FrameCamera& camera, const FrameShape& shape, const RowBand& band, std::uint32_t viewFirst,
                 std::uint32_t viewCount, const RenderSettings& settings);
  // The wavefront frame loop (wavefront_loop.cpp).
  RenderResult render(const FrameCamera& camera, const RenderSettings& settings);
  // `floats` values to overwrite: a recycled buffer that holds them without wasting more than half, else a new one.
  std::vector<float> frameBuffer(std::size_t floats);
  // reusable: the frame is this one chunk without refinement, so it may reuse and keep state (gpu/frame_reuse.h).
  void renderChunk(const FrameCamera& camera, const FrameShape& shape, const RowBand& band, std::uint32_t viewFirst,
                   std::uint32_t viewCount, const RenderSettings& settings, bool reusable, StageTimes& stageMs,
                   RenderResult& result);
  // The samples of a single frame's chunk: the base pass (or the `dirty` targets of a partial re-render, which the
  // marking pass listed), then adaptive refinement.
  void renderChunkSamples(const FrameCamera& camera, const FrameShape& shape, std::uint64_t targets,
                          std::uint64_t dirty, std::uint64_t perBatch, const RenderSettings& settings,
                          StageTimes& stageMs, RenderResult& result);
  // Traces paths [0, totalPaths) of `spp` samples per target in batches of perBatch (a multiple of spp) and resolves
  // them into the subpixel buffer. Refined / Dirty: the listed targets of FrameBlock.refine (refineInfo.w = the base
  // spp when refining, 0 for dirty targets), through the REFINING pipelines of raygen and resolve; else the chunk's
  // base pass. The first call of a frame clears the shadow slots (gather_direct leaves every slot it used cleared for
  // later batches). framePlan says whether the base pass loads or saves the cached primary hits and whether the
  // passes record segment cells.
  void tracePaths(const FrameCamera& camera, const FrameShape& shape, std::uint32_t spp, std::uint64_t totalPaths,
                  std::uint64_t perBatch, TracedTargets which, const RenderSettings& settings, StageTimes& stageMs,
                  const std::function<void(double)>& progress);
  // Closest-hit passes per batch: the primary one, plus maxDepth more when mirrors or glass continue paths.
  std::uint32_t depthPasses(const RenderSettings& settings) const {
    const SceneFeatures& feat = scene.features();
    const bool bounces = feat.mirrors || feat.glass || settings.forceAllFeatures;
    return bounces ? settings.maxDepth + 1 : 1;
  }
  // Frame reuse: copies the queue `depth % 2`, its path indices and the hits of `depth` (>= 1) of the batch from
  // (load) or into the secondary cache (frame_reuse.h), between the passes recorded into `cmd`: the queue's own
  // entries, whose count the frame that fills the cache has read back (secondaryCounts) before this.
  void copySecondary(std::uint32_t depth, std::uint32_t batchFirst, bool load);
  // Frame reuse (partial_retrace.cpp): the key of the frame fillFrame wrote; the marking pass of a partial
  // re-render over the chunk's `targets` (lists the dirty ones in reuse.dirtyList; returns how many), and the
  // re-trace of those `dirty` targets.
  ReuseKey reuseKey(const RenderSettings& settings) const;
  std::uint64_t markMovedTargets(std::uint64_t targets, StageTimes& stageMs);
  // FrameBlock::movedInstanceIds and movedTriangles from ReusePlan::walkedInstances (none unless the scene is on the
  // two-level BVH and movedInstanceWalks, Renderer::setMovedInstanceWalks).
  void writeWalkedInstances(FrameBlock& f) const;
  bool movedInstanceWalks = true;
  bool bounceHitReuse = true;  // Renderer::setBounceHitReuse
  // While a frame fills the bounce cache: the frame block's links for the shade pass of `depth` of the batch from
  // `batchFirst` (FrameBlock::bounceLinks), after that depth's queue took its entries; none once the cache overflowed.
  void setBounceLinks(std::uint32_t depth, std::uint32_t batchFirst);
  void retraceDirty(const FrameCamera& camera, const FrameShape& shape, std::uint64_t dirty, std::uint64_t perBatch,
                    const RenderSettings& settings, StageTimes& stageMs, const std::function<void(double)>& progress);
  // The frame block's reuse members and views for framePlan (after fillFrame and the plan).
  void applyFramePlan(RenderResult& result);
  // The interleave of a partial re-render: only the pixels of its listed targets, whose dirty list it names in the
  // frame block (the caller clears FrameBlock::refine once the pass ran).
  void recordDirtyInterleave(PassRecorder& rec, const FrameShape& shape);
  // Adaptive refinement (refinement_pass.cpp): lists the targets whose contrast reaches `contrast`; returns how many.
  std::uint64_t selectRefinedTargets(const FrameShape& shape, std::uint64_t targets, float contrast,
                                     StageTimes& stageMs);
  std::uint64_t selectTargets(const FrameShape& shape, std::uint64_t targets, float contrast,
                              std::optional<std::uint64_t> listed, bool byError, StageTimes& stageMs);
  // The adaptive policy of progressive accumulation (refinement_pass.cpp): lists the targets the stop rule says need
  // samples, among all the chunk's targets or, given `listed`, among the first `listed` entries of the
  // accumulation's list (FrameBlock::accumList); returns how many.
  std::uint64_t selectUnconvergedTargets(const FrameShape& shape, std::uint64_t targets,
                                         std::optional<std::uint64_t> listed, StageTimes& stageMs);
  // Progressive accumulation (accumulation_pass.cpp).
  RenderResult accumulate(const FrameCamera& camera, const RenderSettings& settings, Accumulator& accumulator);
  void accumulateChunk(const FrameCamera& camera, const FrameShape& shape, const RowBand& band, std::uint32_t viewFirst,
                       std::uint32_t viewCount, const RenderSettings& settings, std::uint64_t perBatch,
                       StageTimes& stageMs, RenderResult& result);
  // The show pass of a progressive frame (accum_show.comp): the first `count` targets of the chunk, or, `listed`,
  // the first `count` entries of the accumulation's list.
  void showTargets(std::uint32_t model, std::uint64_t count, bool listed, StageTimes& stageMs);
  // The progressive members of the frame block (after fillFrame).
  void fillAccumulation(FrameBlock& f, Accumulator& accumulator) const;
  // The marking pass (mark_dirty.comp) over `targets` targets, with the list header, masks and list set in the frame
  // block; resetAccumulation: a dirty target's accumulated sums start over too (partial_retrace.cpp).
  // `list`: the mapped dirty list whose address FrameBlock.refine holds (header: FrameReuseState::kListFirst);
  // `secondary`: the cached queues of depths >= 1 to test entry by entry first (ReusePlan::secondaryExact).
  // `accumulatedCandidates`: in an accumulation (resetAccumulation), the pipeline that tests its candidates
  // (mark_accumulated.comp, raygen's specialisation); otherwise mark_dirty.comp's MARK_CANDIDATES does.
  // `masks`: the segment masks FrameBlock.segmentMasks points at (the frame's or the accumulation's).
  void runMarkingPass(std::uint64_t targets, bool resetAccumulation, const std::uint32_t* list,
                      const DeviceBuffer& masks, StageTimes& stageMs,
                      std::span<const FrameReuseState::SecondaryQueue> secondary = {},
                      const ComputePipeline* accumulatedCandidates = nullptr);
  // Points the reuse texel views (HT_BINDING_REUSE_*) at `masks` and, where the frame keeps them, the cached primary
  // rays and hits and the bounce cache; the others at reuseTexelDummy. Flushes the set. A view must not outlive its
  // buffer while pipelines that use it run: the primary caches are viewed from a frame's plan on (they change only
  // there), the masks and the bounce cache during the marking pass only (runMarkingPass).
  void bindReuseTexels(const DeviceBuffer& masks, bool primaryCached, bool bouncesCached);
  // Points the accumulation's storage texel views (HT_BINDING_ACCUM_*) at `st`'s sums, or (null) at reuseTexelDummy:
  // bound for one accumulate() call, since the sums go with their Accumulator. Flushes the set.
  void bindAccumulation(const Accumulator::State* st);
  // After node moves: lists the targets whose recorded cells meet the moved bounds (their primary segments and the
  // shadow rays from their hits: tested exactly on their samples' regenerated rays) and zeroes their sums and masks
  // (mark_dirty.comp, RESET_ACCUMULATION, then mark_accumulated.comp); returns how many.
  std::uint64_t resetMovedTargets(Accumulator& accumulator, const Bounds3& moved, const FrameCamera& camera,
                                  const FrameShape& shape, std::uint64_t targets, StageTimes& stageMs);
  // Ray batches without a frame (ray_batches.cpp).
  std::vector<gpu_shared::HtRay> generateRays(const FrameCamera& camera, const RenderSettings& settings,
                                              std::uint64_t firstTarget, std::uint32_t targetCount, TraceStats* stats);
  std::vector<gpu_shared::HtHit> traceBatch(std::span<const gpu_shared::HtRay> rays, bool occlusion, TraceStats* stats);
};

}  // namespace ht::gpu
