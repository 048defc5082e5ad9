// embree_tracer.h - the CPU reference tracer of the benchmark: Embree 3 single-ray queries (rtcIntersect1,
// rtcOccluded1) on one triangle mesh, default scene flags and build quality, spread over threads by tiles.
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "bvh/ray_types.h"
#include "scene/scene.h"

namespace ht::bench {

class EmbreeTracer {
 public:
  // Builds the Embree scene from the scene's triangles (all geometry in one mesh). Throws ht::Error on an
  // Embree error.
  explicit EmbreeTracer(const Scene& scene);
  ~EmbreeTracer();
  EmbreeTracer(const EmbreeTracer&) = delete;
  EmbreeTracer& operator=(const EmbreeTracer&) = delete;

  double buildMs() const { return buildMs_; }
  static const char* version();  // "3.13.5"

  // `rays` are `width` rays per row; threads take `tile` x `tile` blocks from a shared counter.
  // Results follow HtHit / traceOccluded conventions: triId = HT_MISS and t = tmax on a miss; 1 = occluded.
  // Each call returns its wall time in *wallMs.
  std::vector<gpu_shared::HtHit> traceClosest(std::span<const gpu_shared::HtRay> rays, std::uint32_t width,
                                              unsigned threads, double* wallMs) const;
  std::vector<std::uint32_t> traceOccluded(std::span<const gpu_shared::HtRay> rays, std::uint32_t width,
                                           unsigned threads, double* wallMs) const;

  // Flat batches (holotrace-bench-traversal): threads take chunks of kFlatChunk consecutive rays. Single =
  // rtcIntersect1/rtcOccluded1 per ray; Packet8 = rtcIntersect8/rtcOccluded8 on 8 consecutive rays
  // (embree_packets.cpp).
  static constexpr std::size_t kFlatChunk = 256;
  enum class Api { Single, Packet8 };
  std::vector<gpu_shared::HtHit> traceClosestFlat(std::span<const gpu_shared::HtRay> rays, Api api, unsigned threads,
                                                  double* wallMs) const;
  std::vector<std::uint32_t> traceOccludedFlat(std::span<const gpu_shared::HtRay> rays, Api api, unsigned threads,
                                               double* wallMs) const;

  struct Handles;  // embree_handles.h

 private:
  std::unique_ptr<Handles> handles_;
  double buildMs_ = 0.0;
};

}  // namespace ht::bench
