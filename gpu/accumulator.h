// accumulator.h - progressive accumulation (docs/REUSE.md §1-§2): per-target sums that persist across the frames
// of one (scene version, display/camera, render settings) on the device, each frame adding samples that continue one
// low-discrepancy sequence, so k frames of N samples equal one frame of k*N samples bit for bit. A per-target error
// estimate (gpu/accumulation_error.h) and a stop rule say when the accumulation has converged; after that a caller
// keeps the last frame and submits no GPU work.
//
// Renderer::accumulate(camera, settings, accumulator) renders one progressive frame: the first frame of an
// accumulation gives every target settings.spp samples; later ones, under the adaptive policy, only the targets the
// stop rule says still need samples (each target keeps its own n; its samples are still indices n.. of its
// sequence), else every target again. When the renderer's scene changed (replaceScene / updateLights), or the
// camera or any setting that shapes a sample did, the accumulation restarts from zero: samples of two scene
// versions are never summed (docs/REUSE.md §5). After node moves whose bounds the renderer was given
// (Renderer::moveNodes with MovedBounds), only the targets whose recorded segment cells meet those bounds restart;
// the others keep their sums, whose samples the move cannot have changed (docs/REUSE.md §4).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "camera_models/frame_camera.h"

namespace ht::gpu {

// The stop rule (docs/REUSE.md §2). A target is converged when it has at least minSpp samples and its error
// estimate is below targetError, or when it has maxSpp samples; the accumulation when every target is.
struct AccumulationPolicy {
  float targetError = 0.02f;
  std::uint32_t minSpp = 8;
  std::uint32_t maxSpp = 256;
  bool adaptive = true;  // after the first frame, add samples only to targets that still need them
};

struct AccumulationReport {
  std::uint32_t minSamples = 0, maxSamples = 0;  // samples per target after the frame
  float maxError = 0.0f;                         // largest per-target error estimate (3e38: not yet judged)
  std::uint64_t targets = 0;                     // targets of the frame
  std::uint64_t unconverged = 0;                 // targets that need more samples
  std::uint64_t tracedTargets = 0;               // targets this frame added samples to
  std::uint32_t frames = 0;                      // frames of this accumulation
  bool restarted = false;                        // this frame began a new accumulation
  std::uint64_t resetTargets = 0;                // after node moves: targets this frame started over (the rest kept)
  bool converged = false;                        // the stop rule holds for every target
};

class Accumulator {
 public:
  // rgb sum + n, half sum + its count (gpu_shared::AccumTarget, 32 B), the segment-cell mask (16 B) and the bounds
  // of its primary segments (reach, nearest and farthest hit: 12 B) that let a node move restart only the targets
  // near it, and its entry in the adaptive policy's list of the targets still sampled (4 B).
  static constexpr std::uint64_t kBytesPerTarget = 64;
  // Device memory an accumulation of `shape` holds.
  static std::uint64_t bytesFor(const FrameShape& shape) { return shape.targets() * kBytesPerTarget; }

  explicit Accumulator(const AccumulationPolicy& policy = {});
  ~Accumulator();
  Accumulator(const Accumulator&) = delete;
  Accumulator& operator=(const Accumulator&) = delete;

  const AccumulationPolicy& policy() const { return policy_; }
  const AccumulationReport& report() const { return report_; }
  bool converged() const { return report_.converged; }
  std::uint64_t deviceBytes() const;
  // The next frame starts a new accumulation (sums and counts zero).
  void restart();
  // The per-target sums as (rgb sum, n, rgb half sum, half count), 8 floats per target of the whole frame (n and
  // the half count as float values): the CPU side of the error-estimate parity test. Empty before the first frame.
  std::vector<float> downloadSums() const;
  // What lets a node move restart only nearby targets, for tests: per target of the whole frame, its kMaskWords
  // segment-cell words (gpu/frame_reuse.h), then kAccumulationBoundWords blocks of a word per target (common.glsl
  // accum_reach_word). Empty while the accumulation records none.
  std::vector<std::uint32_t> downloadMasks() const;
  // The targets the last frame restarted after node moves (the marking pass's list, in its order).
  std::vector<std::uint32_t> lastResetTargets() const;

  struct State;  // the device buffers and what the sums belong to (gpu/renderer_impl.h)
  State& state() { return *state_; }
  AccumulationReport& mutableReport() { return report_; }

 private:
  AccumulationPolicy policy_;
  AccumulationReport report_;
  std::unique_ptr<State> state_;
};

}  // namespace ht::gpu
