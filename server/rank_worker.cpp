// rank_worker.cpp - see rank_worker.h.
#include "server/rank_worker.h"

#include <signal.h>

#include <chrono>
#include <map>
#include <memory>
#include <thread>

#include "cluster/cluster_error.h"
#include "cluster/rank_identity.h"
#include "cluster/scene_bytes.h"
#include "cluster/work_dispatch.h"
#include "gpu/vulkan_context.h"
#include "server/cluster_job.h"
#include "server/display_registry.h"
#include "server/frame_job.h"
#include "server/scene_library.h"

namespace ht::server {
namespace {

using Clock = std::chrono::steady_clock;

// True when a stop signal is pending for this thread (blocked signals stay pending until taken here).
bool takeStopSignal() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGHUP);
  const timespec now{0, 0};
  const int sig = sigtimedwait(&set, nullptr, &now);
  return sig == SIGTERM || sig == SIGINT;
}

// Polls for rank 0's next job with 1 ms sleeps, so an idle rank takes no core. Throws when a stop signal was not
// followed by rank 0's stop within kStopWaitSeconds.
ClusterJob awaitJob(cluster::Communicator& comm) {
  std::optional<Clock::time_point> stopBy;
  for (;;) {
    if (const std::optional<cluster::Incoming> message = comm.probe()) {
      if (message->source != 0 || message->tag != kClusterJobTag) {
        throw cluster::ClusterError("rank " + std::to_string(message->source) +
                                    " sent a message outside a frame (tag " + std::to_string(message->tag) + ")");
      }
      cluster::receiveRecord<std::uint64_t>(comm, 0, kClusterJobTag);
      std::vector<std::uint8_t> bytes;
      comm.broadcast(bytes, 0);
      return decodeClusterJob(bytes);
    }
    if (!stopBy && takeStopSignal()) {
      stopBy =
          Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kStopWaitSeconds));
    }
    if (stopBy && Clock::now() > *stopBy) {
      throw cluster::ClusterError("got a stop signal, but rank 0 sent no stop within " +
                                  std::to_string(static_cast<int>(kStopWaitSeconds)) + " s");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

// The scene versions rank 0 sent, each with its Renderer (BVH built here).
class RankScenes {
 public:
  explicit RankScenes(gpu::VulkanContext& context) : context_(context) {}
  std::shared_ptr<SceneContent> update(const ClusterJob& job) {
    for (const std::uint64_t version : job.dropVersions) scenes_.erase(version);
    if (!job.sceneBytes.empty()) {
      auto content = std::make_shared<SceneContent>();
      content->scene = cluster::decodeScene(job.sceneBytes);
      content->loadBounds = job.loadBounds;
      content->renderer = std::make_shared<gpu::Renderer>(context_, content->scene);
      scenes_[job.sceneVersion] = std::move(content);
    }
    auto it = scenes_.find(job.sceneVersion);
    if (it == scenes_.end()) {
      throw cluster::ClusterError("rank 0 asked for scene version " + std::to_string(job.sceneVersion) +
                                  ", which this rank never received");
    }
    it->second->loadBounds = job.loadBounds;
    return it->second;
  }

 private:
  gpu::VulkanContext& context_;
  std::map<std::uint64_t, std::shared_ptr<SceneContent>> scenes_;
};

// The FrameJob rank 0 rendered, rebuilt here: the same functions then give the same camera.
FrameJob frameJobOf(const ClusterJob& job, std::shared_ptr<SceneContent> content, DisplayRegistry& displays,
                    std::ostream& log) {
  auto session = std::make_shared<SceneSession>();
  session->content = std::move(content);
  session->cameraOverride.target = job.cameraTarget;
  session->cameraOverride.size = job.cameraSize;
  session->observerDistance = job.observerDistance;
  session->observerHeight = job.observerHeight;
  FrameJob frame;
  frame.session = std::move(session);
  frame.path = job.path;
  try {
    frame.display = displays.find(job.displayId);
  } catch (const UnknownDisplay&) {
    displays.reload(log);  // rank 0 reloaded its displays (SIGHUP): so do we
    frame.display = displays.find(job.displayId);
  }
  return frame;
}

gpu::DisplayCamera checkedCamera(const ClusterJob& job, FrameJob& frame, DisplayRegistry& displays, std::ostream& log) {
  gpu::DisplayCamera camera = jobCamera(frame);
  if (cluster::displayDigest(job.displayId, camera) == job.cameraDigest) return camera;
  displays.reload(log);
  frame.display = displays.find(job.displayId);
  camera = jobCamera(frame);
  if (cluster::displayDigest(job.displayId, camera) != job.cameraDigest) {
    throw cluster::ClusterError("display '" + job.displayId +
                                "' resolves to another camera on this rank than on rank 0: give every rank the "
                                "same display configs (displays_dir)");
  }
  return camera;
}

void renderShare(cluster::Communicator& comm, const ClusterJob& job, const FrameJob& frame,
                 const gpu::DisplayCamera& camera) {
  const std::vector<cluster::WorkUnit> units = clusterFrameUnits(camera.shape, job.settings, comm.size());
  gpu::Renderer& renderer = *frame.session->content->renderer;
  const auto renderUnit = [&](const cluster::WorkUnit& unit) {
    return renderClusterUnit(renderer, camera, job.settings, unit);
  };
  cluster::dispatchWork(comm, units, renderUnit, [](std::size_t, std::vector<float>&&) {});
}

}  // namespace

void runWorkerRank(cluster::Communicator& comm, const DaemonConfig& config, std::ostream& log) {
  gpu::VulkanContext context({config.deviceIndex, false});
  DisplayRegistry displays(config.displaysDir, deviceScanFor(config.devices));
  displays.reload(log);
  RankScenes scenes(context);
  for (;;) {
    const ClusterJob job = awaitJob(comm);
    if (job.kind == ClusterJob::Kind::Stop) return;
    FrameJob frame = frameJobOf(job, scenes.update(job), displays, log);
    const gpu::DisplayCamera camera = checkedCamera(job, frame, displays, log);
    renderShare(comm, job, frame, camera);
  }
}

}  // namespace ht::server
