// renderer.h - the public GPU API: upload a scene once, then render display frames or trace ray batches.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "bvh/bvh_builder.h"
#include "bvh/ray_types.h"
#include "camera_models/camera_params.h"
#include "scene/scene.h"

namespace ht::gpu {

class VulkanContext;

struct RenderSettings {
  std::uint32_t spp = 4;          // samples per subpixel (lenticular) or pixel (pinhole)
  std::uint32_t maxDepth = 4;     // specular bounces (mirror/glass) after the primary hit
  bool forceAllFeatures = false;  // disable scene specialisation (benchmark of the skipping)
  std::uint32_t seed = 0;         // decorrelates sample patterns; same seed -> bit-identical frame
  std::function<void(double fractionDone)> progress;  // called after each batch of paths (optional)
};

struct StageTiming {
  std::string name;  // "raygen", "trace", "shade", "shadow", "resolve", "interleave", "readback", ...
  double ms = 0.0;   // GPU timestamp time summed over batches/bounces (readback: host wall time)
};

struct RenderResult {
  std::uint32_t width = 0, height = 0;
  std::vector<float> rgba;            // linear RGBA float, row 0 = image TOP, 4 floats per pixel
  std::vector<StageTiming> stages;
  double totalMs = 0.0;               // host wall time of the frame
  std::uint64_t raysTraced = 0;       // closest-hit + any-hit rays
  std::uint32_t maxTraversalSteps = 0;
  std::uint32_t nonFiniteSamples = 0; // targets whose value was NaN/Inf and was written as 0 (should be 0)
};

struct TraceStats {
  double gpuMs = 0.0;                 // timestamp time of the trace dispatches only
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

  // Native interleaved panel image (screenW x screenH), each subpixel traced with its own rays.
  RenderResult renderLenticular(const gpu_shared::LenticularParams& params, const RenderSettings& settings);
  // Ordinary RGB image through a pinhole camera.
  RenderResult renderPinhole(const gpu_shared::PinholeParams& params, const RenderSettings& settings);

  // Closest-hit / any-hit for a user batch (parity tests, `raycast`). Throws GpuError if a ray exceeded the
  // traversal step limit (the lavapipe loop cap), naming how many rays did.
  std::vector<gpu_shared::HtHit> traceClosest(std::span<const gpu_shared::HtRay> rays, TraceStats* stats = nullptr);
  std::vector<std::uint32_t> traceOccluded(std::span<const gpu_shared::HtRay> rays, TraceStats* stats = nullptr);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace ht::gpu
