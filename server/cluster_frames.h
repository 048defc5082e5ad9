// cluster_frames.h - rank 0's side of holotraced under mpirun (docs/CLUSTER.md §8): every frame job is announced to
// the other ranks (a wake-up message each, then one broadcast of the ClusterJob, server/cluster_job.h), its work
// units are handed out dynamically (cluster/work_dispatch.h; rank 0 renders units too) and assembled here
// (cluster/frame_assembly.h) into the one frame that the RPC sends or writes as a single process would.
//
// Scene versions: a published SceneContent never changes (server/scene_library.h), so each content rank 0 renders
// gets a version number; its bytes (cluster/scene_bytes.h) go with the first frame job that needs it, and the ranks
// build their own BVH from them. When rank 0 lets go of a content, the next job tells the ranks to drop it too.
//
// An error after a job was announced leaves the other ranks inside the protocol: the whole job is then ended
// (Communicator::abort), every rank exits non-zero, and clients see their connection close (UNAVAILABLE).
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "cluster/communicator.h"
#include "cluster/work_dispatch.h"
#include "server/cluster_job.h"
#include "server/distributed_frames.h"
#include "server/scene_library.h"

namespace ht::server {

// Who each rank is (rank order), exchanged at start (server/cluster_start.h).
struct RankInfo {
  std::string host;
  std::uint32_t pid = 0;
};

class ClusterFrames final : public DistributedFrames {
 public:
  ClusterFrames(cluster::Communicator& comm, std::vector<RankInfo> ranks, std::ostream& log);
  ~ClusterFrames() override;  // stop()

  gpu::RenderResult render(const FrameJob& job, const gpu::DisplayCamera& camera,
                           const gpu::RenderSettings& settings) override;
  ClusterTimings timings() const override;
  void stop() override;

 private:
  ClusterJob jobFor(const FrameJob& job, const gpu::DisplayCamera& camera, const gpu::RenderSettings& settings);
  std::uint64_t versionOf(const std::shared_ptr<SceneContent>& content, bool& fresh);
  void announce(const ClusterJob& job, std::uint64_t& bytes);
  void record(const cluster::DispatchReport& report, double frameMs, double broadcastMs, std::uint64_t bytes,
              std::size_t units, bool sceneSent);
  void markOtherRanks(const char* state);
  [[noreturn]] void endJob(const std::exception& error);

  struct Version {
    std::weak_ptr<SceneContent> content;
    std::uint64_t number = 0;
  };
  cluster::Communicator& comm_;
  std::ostream& log_;
  std::map<const SceneContent*, Version> versions_;  // render worker thread only
  std::uint64_t nextVersion_ = 1;
  bool stopped_ = false;
  mutable std::mutex mutex_;  // timings_ (Status reads them from gRPC threads)
  ClusterTimings timings_;
};

}  // namespace ht::server
