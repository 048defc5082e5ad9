// renderer.h - the public GPU API: upload a scene once, then render display frames or trace ray batches.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "bvh/bvh_builder.h"
#include "bvh/ray_types.h"
#include "camera_models/camera_params.h"
#include "camera_models/capture_grid_params.h"
#include "camera_models/integral_params.h"
#include "camera_models/oblique_params.h"
#include "camera_models/projector_params.h"
#include "camera_models/quilt_params.h"
#include "camera_models/ray_table.h"
#include "scene/scene.h"

namespace ht::gpu {

class VulkanContext;

// Reconstruction filter over each pixel / subpixel footprint, applied by warping the samples
// (camera_models/footprint_sampling.h).
enum class SampleFilter : std::uint32_t { Box = 0, Tent = 1, Gaussian = 2 };

// A per-pixel ray table and its placement; the table is uploaded once per table object (shared_ptr identity).
struct RayTableCamera {
  gpu_shared::RayTableParams params{};
  std::shared_ptr<const RayTable> table;
};

// The camera of a frame. The alternative selects the ray-generation model (specialisation constant of raygen).
using FrameCamera = std::variant<gpu_shared::LenticularParams, gpu_shared::PinholeParams, gpu_shared::QuiltParams,
                                 gpu_shared::ProjectorArrayParams, gpu_shared::IntegralParams,
                                 gpu_shared::CaptureGridParams, gpu_shared::ObliqueParams, RayTableCamera>;

// What a camera renders: `views` images of width x height pixels; subpixel models trace 3 targets per pixel.
struct FrameShape {
  std::uint32_t model = 0;  // gpu_shared::HT_MODEL_*
  std::uint32_t width = 0, height = 0, views = 1;
  std::uint32_t targetsPerPixel = 1;
  std::uint64_t targets() const { return static_cast<std::uint64_t>(width) * height * views * targetsPerPixel; }
};
FrameShape frameShape(const FrameCamera& camera);

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
  std::function<void(double fractionDone)> progress;  // called after each batch of paths (optional)
};

struct StageTiming {
  std::string name;  // "raygen", "trace", "shade", "shadow", "resolve", "interleave", "readback", ...
  double ms = 0.0;   // GPU timestamp time summed over batches/bounces (readback: host wall time)
};

struct RenderResult {
  std::uint32_t width = 0, height = 0;  // of one view
  std::uint32_t views = 1;
  std::vector<float> rgba;  // linear RGBA float, view after view, row 0 = the view's TOP, 4 floats per pixel
  std::vector<StageTiming> stages;
  double totalMs = 0.0;          // host wall time of the frame
  std::uint64_t raysTraced = 0;  // closest-hit + any-hit rays
  std::uint32_t maxTraversalSteps = 0;
  std::uint32_t nonFiniteSamples = 0;  // targets whose value was NaN/Inf and was written as 0 (should be 0)
  std::uint64_t refinedTargets = 0;    // targets traced again by adaptive refinement (RenderSettings::refineSpp)
};

struct TraceStats {
  double gpuMs = 0.0;  // timestamp time of the trace dispatches only
  std::uint32_t maxSteps = 0;
};

class Renderer {
 public:
  Renderer(VulkanContext& context, const Scene& scene, const bvh::BuildOptions& buildOptions = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const bvh::BuildReport& bvhReport() const;
  const SceneFeatures& features() const;
  // Rebuilds the BVH and re-uploads the scene (an edited copy: moved nodes, changed lights) with the build options
  // given at construction; the compiled pipelines are kept, so the next frame costs no shader compilation.
  void replaceScene(const Scene& scene);
  // Re-uploads only the lights of `scene`, which must be this Renderer's scene with edited light values (same light
  // count; throws GpuError otherwise): a light edit needs no BVH.
  void updateLights(const Scene& scene);

  // Every view of the camera. Large view arrays are rendered in chunks of views (bounded device memory).
  RenderResult render(const FrameCamera& camera, const RenderSettings& settings);
  // Native interleaved panel image (screenW x screenH), each subpixel traced with its own rays.
  RenderResult renderLenticular(const gpu_shared::LenticularParams& params, const RenderSettings& settings);
  // Ordinary RGB image through a pinhole camera.
  RenderResult renderPinhole(const gpu_shared::PinholeParams& params, const RenderSettings& settings);
  // The N quilt views (tile size each), view 0 = leftmost camera.
  RenderResult renderQuilt(const gpu_shared::QuiltParams& params, const RenderSettings& settings);

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

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace ht::gpu
