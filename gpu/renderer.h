// renderer.h - the public GPU API: upload a scene once, then render display frames or trace ray batches.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "bvh/bvh_builder.h"
#include "bvh/gpu_layout.h"
#include "bvh/ray_types.h"
#include "camera_models/frame_camera.h"
#include "camera_models/ray_table.h"
#include "gpu/accumulator.h"
#include "gpu/scene_bvh.h"
#include "gpu/segment_cells.h"
#include "scene/scene.h"
#include "scene/scene_edits.h"

namespace ht::gpu {

class VulkanContext;

// Reconstruction filter over each pixel / subpixel footprint, applied by warping the samples
// (camera_models/footprint_sampling.h).
enum class SampleFilter : std::uint32_t { Box = 0, Tent = 1, Gaussian = 2 };

// The camera of a frame, its shape and GPU block: camera_models/frame_camera.h (no Vulkan there).
using ht::FrameCamera;
using ht::FrameShape;
using ht::frameShape;
using ht::RayTableCamera;

// The part of the frame to render: views [viewFirst, viewFirst + viewCount) and, of each, the output rows
// [rowFirst, rowFirst + rowCount) (row 0 = the top, as in RenderResult); a count of 0 means "to the end". Sample
// positions and random choices are keyed by a target's index in the whole frame, so every pixel of a region is
// bit-identical to the same pixel of a whole-frame render: the work unit of a cluster render (cluster/work_plan.h).
// Adaptive refinement compares neighbour rows, so a band of rows with refineSpp > 0 is refused (GpuError).
struct RenderRegion {
  std::uint32_t viewFirst = 0, viewCount = 0;
  std::uint32_t rowFirst = 0, rowCount = 0;
};

struct RenderSettings {
  std::uint32_t spp = 4;  // samples per target (subpixel or pixel)
  SampleFilter filter = SampleFilter::Box;
  std::uint32_t maxDepth = 4;     // specular bounces (mirror/glass) after the primary hit
  bool forceAllFeatures = false;  // disable scene specialisation (benchmark of the skipping)
  std::uint32_t seed = 0;         // decorrelates sample patterns; same seed -> bit-identical frame
  // Adaptive refinement (gpu/adaptive_refinement.h): after the frame at `spp`, every target whose sRGB value differs
  // from a same-channel neighbour pixel by >= refineContrast is traced again at refineSpp samples, and takes the mean
  // of all its spp + refineSpp samples. refineSpp 0 = off; refineContrast 0 refines every target, > 1 none.
  std::uint32_t refineSpp = 0;
  float refineContrast = 0.08f;
  RenderRegion region;  // default: the whole frame
  // Keep what the next frame of the same view can reuse after an edit (docs/REUSE.md §3, §4): the primary rays and
  // hits of every sample (48 B per path, up to kPrimaryHitCacheBudget) and per target the world-grid cells its path
  // segments met (8 B per target). Then a frame after updateLights re-shades the cached hits without raygen and
  // primary trace, and a frame after replaceSceneAfterMove re-traces only the targets whose segments may meet the
  // moved bounds; both equal a full render of the edited scene bit for bit. Only frames of one chunk of views
  // without adaptive refinement keep state; others render in full.
  bool reuse = false;
  // A node move re-renders partially while its marking pass lists at most this share of the frame's targets; a
  // larger one renders the frame in full (recording the state afresh): a listed target costs 1.3-1.5x a target of
  // a full frame, so past about 0.7-0.8 of the targets the partial frame is the dearer one (docs/REUSE.md §4 "When
  // a move dirties most targets"). [0, 1]; 1: always partially.
  double reuseMaxDirtyShare = 0.75;
  // Paths per batch at most (0: the renderer's own limit, about a million paths): smaller values split a frame into
  // more batches without changing its bits (tests of batching).
  std::uint32_t maxPathsPerBatch = 0;
  std::function<void(double fractionDone)> progress;  // called after each batch of paths (optional)
};

struct StageTiming {
  std::string name;  // "raygen", "trace", "shade", "shadow", "resolve", "interleave", "readback", ...
  double ms = 0.0;   // GPU timestamp time summed over batches/bounces (readback: host wall time)
};

// What a frame took from the previous frame of the same view (RenderSettings::reuse).
enum class FrameReuse : std::uint32_t {
  None,               // rendered in full
  CachedPrimaryHits,  // the light values changed (or nothing did): re-shaded from the cached primary hits
  PartialRetrace,     // a node moved: only the targets whose path segments could meet it were traced again
};

struct RenderResult {
  std::uint32_t width = 0, height = 0;  // of one view (of its band of rows when RenderSettings::region has one)
  std::uint32_t views = 1;              // rendered views (RenderSettings::region's count)
  std::vector<float> rgba;  // linear RGBA float, view after view, row 0 = the view's TOP, 4 floats per pixel
  std::vector<StageTiming> stages;
  double totalMs = 0.0;          // host wall time of the frame
  std::uint64_t raysTraced = 0;  // closest-hit + any-hit rays
  std::uint32_t maxTraversalSteps = 0;
  std::uint32_t nonFiniteSamples = 0;  // targets whose value was NaN/Inf and was written as 0 (should be 0)
  std::uint64_t refinedTargets = 0;    // targets traced again by adaptive refinement (RenderSettings::refineSpp)
  AccumulationReport accumulation;     // Renderer::accumulate only
  FrameReuse reuse = FrameReuse::None;
  std::uint64_t tracedTargets = 0;  // targets whose samples this frame computed (PartialRetrace: the dirty ones)
};

// Which BVH layout the Renderer traces and how its BVH changed since construction (tests and benchmarks: a node
// move on a two-level scene must not rebuild).
struct BvhStats {
  bvh::BvhLayout layout = bvh::BvhLayout::Flattened;
  std::uint64_t fullBuilds = 0;       // BVHs built and uploaded whole (construction counts one)
  std::uint64_t instanceUpdates = 0;  // moveNodes served by refit + top-level rebuild + partial upload
  double lastUpdateMs = 0.0;          // host wall time of the last replaceScene / moveNodes, uploads included
  double lastRefitMs = 0.0;           // of the last moveNodes on the two-level BVH: refit of the moved instances
  double lastTopLevelMs = 0.0;        // the top-level rebuild
  double lastUploadMs = 0.0;          // and the upload of the changed ranges (all three included in lastUpdateMs)
};

// Where moved geometry was and is (Renderer::moveNodes): its bounds, and, when one node moved, balls around it
// (scene/scene_edits.h nodeWorldBall; w < 0: not given), by which the marking pass passes over the segments that
// cross only the corners of the bounds (docs/REUSE.md §4 "Balls around the moved node").
struct MovedBounds {
  Bounds3 before, after;
  glm::vec4 beforeBall = kNoBall, afterBall = kNoBall;
};

struct TraceStats {
  double gpuMs = 0.0;  // timestamp time of the trace dispatches only
  std::uint32_t maxSteps = 0;
};

// One closest-hit segment of depth >= 1 as the frame-reuse cache keeps it, with the target of its path (tests).
struct SecondarySegment {
  gpu_shared::HtRay ray;
  gpu_shared::HtHit hit;
  std::uint32_t target;
};

class Renderer {
 public:
  Renderer(VulkanContext& context, const Scene& scene, const bvh::BuildOptions& buildOptions = {});
  // With `bvh` = bvh::buildGpuBvh(scene, buildOptions) built beforehand, off the thread that owns the device (the
  // daemon's render worker keeps rendering other clients' frames meanwhile); the same frames as above.
  Renderer(VulkanContext& context, const Scene& scene, bvh::GpuBvh bvh, const bvh::BuildOptions& buildOptions = {});
  // With the BVH built beforehand in the layout of the caller's choice (buildSceneBvh, gpu/scene_bvh.h). The first
  // constructor chooses automatically (BvhLayoutPolicy::Automatic); frames are the same bits in either layout.
  Renderer(VulkanContext& context, const Scene& scene, SceneBvh bvh, const bvh::BuildOptions& buildOptions = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const bvh::BuildReport& bvhReport() const;
  const SceneFeatures& features() const;
  // Rebuilds the BVH (in the layout `policy` gives) and re-uploads the scene (an edited copy: moved nodes, changed
  // lights) with the build options given at construction; the compiled pipelines are kept, so the next frame costs no
  // shader compilation.
  void replaceScene(const Scene& scene, BvhLayoutPolicy policy = BvhLayoutPolicy::Automatic);
  // Re-uploads only the lights of `scene`, which must be this Renderer's scene with edited light values (same light
  // count; throws GpuError otherwise): a light edit needs no BVH.
  void updateLights(const Scene& scene);
  // `scene` is this Renderer's scene with nodes `nodes` (indices into scene.nodes) moved by setNodeWorldMatrix. On the
  // two-level BVH: a refit of the moved instances, a top-level rebuild and an upload of what changed (no rebuild). On
  // the flattened BVH: the scene switches to the two-level BVH (built whole once; later moves take the fast path).
  // Frame reuse (RenderSettings::reuse): with `moved` (the moved nodes' world bounds before and after, e.g. unions of
  // nodeWorldBounds, scene/scene_edits.h) the next frame of the same view re-traces only the targets whose last path
  // segments met a grid cell of those bounds (docs/REUSE.md §4); without it, the next frame renders whole.
  void moveNodes(const Scene& scene, std::span<const std::uint32_t> nodes, std::optional<MovedBounds> moved = {});
  BvhStats bvhStats() const;
  // replaceScene (a full BVH rebuild) after an edit that changed geometry only inside `oldBounds` and `newBounds` (a
  // node moved: its world bounds before and after, e.g. nodeWorldBounds in scene/scene_edits.h): with
  // RenderSettings::reuse the next frame of the same view re-traces only the targets whose last path segments met a
  // grid cell of those bounds.
  void replaceSceneAfterMove(const Scene& scene, const Bounds3& oldBounds, const Bounds3& newBounds);

  // Every view of the camera, whatever its model (camera_models/frame_camera.h). Large view arrays are rendered in
  // chunks of views (bounded device memory).
  RenderResult render(const FrameCamera& camera, const RenderSettings& settings);

  // One progressive frame (gpu/accumulator.h): adds settings.spp samples per target (per listed target under the
  // adaptive policy) to `accumulator`'s sums and returns sum / n per target. refineSpp must be 0 (the accumulator's
  // policy decides where samples go). Restarts the accumulation when this renderer's scene, the camera or a setting
  // that shapes samples changed since its last frame.
  RenderResult accumulate(const FrameCamera& camera, const RenderSettings& settings, Accumulator& accumulator);

  // Gives a frame's pixels (RenderResult::rgba) back for the next render() or accumulate() to write into. A loop
  // that renders frame after frame then reuses one host buffer instead of allocating a new one each time: for the
  // Portrait that is 50 MB of fresh pages, whose first touch costs more than the copy into them (docs/BENCHMARKS.md
  // "Host buffers of a frame loop": a cost outside the GPU's stages). Keeps the last two buffers
  // (a loop that holds one frame while it renders the next needs two); safe to call from another thread than the
  // one rendering.
  void recycle(std::vector<float>&& rgba);

  // The primary rays raygen writes for targets [firstTarget, firstTarget + targetCount), settings.spp samples each
  // (sample s of target t at index (t - firstTarget)*spp + s), read back without tracing them: the GPU side of
  // the float-vs-double ray tests, `holotrace rays`, and the ray-generation benchmark (stats->gpuMs = raygen time).
  std::vector<gpu_shared::HtRay> generateRays(const FrameCamera& camera, const RenderSettings& settings,
                                              std::uint64_t firstTarget, std::uint32_t targetCount,
                                              TraceStats* stats = nullptr);

  // Closest-hit / any-hit for a user batch (parity tests, `raycast`). Throws GpuError if a ray exceeded the
  // traversal step limit (the lavapipe loop cap), naming how many rays did.
  std::vector<gpu_shared::HtHit> traceClosest(std::span<const gpu_shared::HtRay> rays, TraceStats* stats = nullptr);
  std::vector<std::uint32_t> traceOccluded(std::span<const gpu_shared::HtRay> rays, TraceStats* stats = nullptr);

  // The frame-reuse state (RenderSettings::reuse) for tests and benchmarks: per-target segment cells of the last
  // frame that kept state (4 words per target, gpu/frame_reuse.h kMaskWords), the grid they are counted on, the cached
  // primary rays and hits (empty when not cached), the targets the last partial re-render traced (in the marking
  // pass's order) with what that pass tested. Empty when no state is kept.
  struct ReuseSnapshot {
    std::vector<std::uint32_t> segmentMasks, dirtyTargets;
    std::vector<gpu_shared::HtRay> primaryRays;
    std::vector<gpu_shared::HtHit> primaryHits;
    // The secondary cache's entries (depths >= 1) while the marking pass may test them (ReusePlan::secondaryExact),
    // and whether the last partial re-render did.
    std::vector<SecondarySegment> secondarySegments;
    bool secondaryExact = false;
    gpu_shared::SegmentGrid grid{};
    // The last partial re-render's moved cells, padded moved bounds and balls (what its marking pass tested).
    std::uint32_t movedCells[2] = {0, 0};
    glm::vec3 movedLo{0.0f}, movedHi{0.0f};
    glm::vec4 movedBalls[2] = {kNoBall, kNoBall};
  };
  ReuseSnapshot reuseSnapshot() const;
  // Device memory the frame-reuse state may give its cache of mirror and glass bounces (default
  // kSecondaryHitCacheBudget, gpu/frame_reuse.h); from the next frame that records it on. A frame whose bounces do not
  // fit keeps no state, and the frames of its view after it record without that cache.
  void setBounceCacheBudget(std::uint64_t bytes);
  // Whether a partial re-render's traced rays walk from their cached hits on the two-level BVH: the moved instances
  // alone when that hit is on none of them, the others only beyond it when it is on one; and whether its shadow rays
  // that were unoccluded before the move walk the moved instances alone (default on; docs/REUSE.md §4). Off traces
  // them whole, the same bits: for same-run comparisons.
  void setMovedInstanceWalks(bool on);
  // Whether a partial re-render's bounce rays that are their paths' cached rays take the cached hits where the move
  // cannot have changed them (default on; docs/REUSE.md §4). Off traces them, the same bits: for same-run
  // comparisons.
  void setBounceHitReuse(bool on);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace ht::gpu
