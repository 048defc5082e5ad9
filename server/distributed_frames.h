// distributed_frames.h - the frame path of holotraced launched under mpirun (docs/CLUSTER.md §8): the pixels of a
// frame job made by every rank of the MPI job instead of by this process's renderer alone. A FrameJob carries a
// pointer to it (FrameJob::cluster; null in a single-process daemon, which renders exactly as before). The server
// sees only this interface; server/cluster_frames.h implements it over ht_cluster's communicator (no MPI here).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "gpu/display_camera.h"
#include "gpu/renderer.h"

namespace ht::server {

struct FrameJob;

// One rank's share of the last distributed frame and since start (proto RankStatus).
struct RankTimings {
  std::uint32_t rank = 0;
  std::string host;
  std::uint32_t pid = 0;
  std::string state;  // "serving" (rank 0), "ready", "rendering"
  double lastBusyMs = 0.0, lastIdleMs = 0.0, totalBusyMs = 0.0;
  std::uint32_t lastUnits = 0;
  std::uint64_t totalUnits = 0;
};

// The last distributed frame as rank 0 measured it (proto ClusterFrameStatus).
struct ClusterTimings {
  std::uint64_t frames = 0;
  double lastFrameMs = 0.0, lastBroadcastMs = 0.0, lastGatherMs = 0.0;
  std::uint64_t lastBroadcastBytes = 0, lastGatherBytes = 0, sceneBroadcasts = 0;
  std::uint32_t workUnits = 0;
  std::vector<RankTimings> ranks;
};

class DistributedFrames {
 public:
  virtual ~DistributedFrames() = default;
  // Renders `job` (traced content: it has a Renderer) with `camera` and `settings` on every rank; the result is the
  // whole frame, bit-identical to this process rendering it alone. Runs on the render worker thread.
  virtual gpu::RenderResult render(const FrameJob& job, const gpu::DisplayCamera& camera,
                                   const gpu::RenderSettings& settings) = 0;
  virtual ClusterTimings timings() const = 0;
  // Ends the other ranks cleanly (the daemon's shutdown, after the render worker stopped). Idempotent.
  virtual void stop() = 0;
};

}  // namespace ht::server
