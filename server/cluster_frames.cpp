// cluster_frames.cpp - see cluster_frames.h.
#include "server/cluster_frames.h"

#include <chrono>
#include <cstdlib>
#include <iostream>

#include "cluster/frame_assembly.h"
#include "cluster/rank_identity.h"
#include "cluster/scene_bytes.h"
#include "server/frame_job.h"

namespace ht::server {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

ClusterFrames::ClusterFrames(cluster::Communicator& comm, std::vector<RankInfo> ranks, std::ostream& log)
    : comm_(comm), log_(log) {
  for (std::size_t r = 0; r < ranks.size(); ++r) {
    RankTimings t;
    t.rank = static_cast<std::uint32_t>(r);
    t.host = ranks[r].host;
    t.pid = ranks[r].pid;
    t.state = r == 0 ? "serving" : "ready";
    timings_.ranks.push_back(std::move(t));
  }
}

ClusterFrames::~ClusterFrames() { stop(); }

std::uint64_t ClusterFrames::versionOf(const std::shared_ptr<SceneContent>& content, bool& fresh) {
  auto it = versions_.find(content.get());
  fresh = it == versions_.end() || it->second.content.lock() != content;  // an old content's address reused
  if (!fresh) return it->second.number;
  versions_[content.get()] = Version{content, nextVersion_};
  return nextVersion_++;
}

ClusterJob ClusterFrames::jobFor(const FrameJob& job, const gpu::DisplayCamera& camera,
                                 const gpu::RenderSettings& settings) {
  ClusterJob message;
  for (auto it = versions_.begin(); it != versions_.end();) {  // contents rank 0 let go of
    if (it->second.content.expired()) {
      message.dropVersions.push_back(it->second.number);
      it = versions_.erase(it);
    } else {
      ++it;
    }
  }
  const std::shared_ptr<SceneContent>& content = job.session->content;
  bool fresh = false;
  message.sceneVersion = versionOf(content, fresh);
  if (fresh) message.sceneBytes = cluster::encodeScene(content->scene);
  message.loadBounds = content->loadBounds;
  message.displayId = job.display->id;
  message.cameraDigest = cluster::displayDigest(job.display->id, camera);
  message.cameraTarget = job.session->cameraOverride.target;
  message.cameraSize = job.session->cameraOverride.size;
  message.observerDistance = job.session->observerDistance;
  message.observerHeight = job.session->observerHeight;
  message.path = job.path;
  message.settings = settings;
  return message;
}

void ClusterFrames::announce(const ClusterJob& job, std::uint64_t& bytes) {
  std::vector<std::uint8_t> encoded = encodeClusterJob(job);
  bytes = encoded.size();
  // A wake-up each (idle ranks poll for it with short sleeps instead of spinning inside a collective), then one
  // broadcast, which Open MPI spreads over a tree.
  for (int r = 1; r < comm_.size(); ++r) cluster::sendRecord(comm_, r, kClusterJobTag, std::uint64_t{bytes});
  comm_.broadcast(encoded, 0);
}

gpu::RenderResult ClusterFrames::render(const FrameJob& job, const gpu::DisplayCamera& camera,
                                        const gpu::RenderSettings& settings) {
  const auto start = Clock::now();
  const ClusterJob message = jobFor(job, camera, settings);
  gpu::Renderer& renderer = *job.session->content->renderer;
  try {
    markOtherRanks("rendering");
    std::uint64_t bytes = 0;
    announce(message, bytes);
    const double broadcastMs = msSince(start);
    const std::vector<cluster::WorkUnit> units = clusterFrameUnits(camera.shape, settings, comm_.size());
    cluster::FrameAssembly assembly(camera.shape, units);
    const auto renderUnit = [&](const cluster::WorkUnit& unit) {
      return renderClusterUnit(renderer, camera, settings, unit);
    };
    const auto place = [&](std::size_t unit, std::vector<float>&& rgba) { assembly.place(unit, rgba); };
    const cluster::DispatchReport report = cluster::dispatchWork(comm_, units, renderUnit, place);
    gpu::RenderResult result = assembly.take(0);
    result.totalMs = msSince(start);
    result.stages = {{"cluster-broadcast", broadcastMs},
                     {"cluster-units", report.wallMs - report.gatherMs},
                     {"cluster-gather", report.gatherMs}};
    record(report, result.totalMs, broadcastMs, bytes, units.size(), !message.sceneBytes.empty());
    markOtherRanks("ready");
    return result;
  } catch (const std::exception& e) { endJob(e); }
}

void ClusterFrames::record(const cluster::DispatchReport& report, double frameMs, double broadcastMs,
                           std::uint64_t bytes, std::size_t units, bool sceneSent) {
  std::lock_guard lock(mutex_);
  ClusterTimings& t = timings_;
  ++t.frames;
  t.lastFrameMs = frameMs;
  t.lastBroadcastMs = broadcastMs;
  t.lastBroadcastBytes = bytes;
  t.lastGatherMs = report.gatherMs;
  t.lastGatherBytes = report.gatherBytes;
  t.workUnits = static_cast<std::uint32_t>(units);
  if (sceneSent) ++t.sceneBroadcasts;
  for (std::size_t r = 0; r < t.ranks.size() && r < report.ranks.size(); ++r) {
    RankTimings& rank = t.ranks[r];
    rank.lastBusyMs = report.ranks[r].busyMs;
    rank.lastUnits = report.ranks[r].units;
    rank.lastIdleMs = std::max(0.0, report.wallMs - rank.lastBusyMs);
    rank.totalBusyMs += rank.lastBusyMs;
    rank.totalUnits += rank.lastUnits;
  }
}

void ClusterFrames::markOtherRanks(const char* state) {
  std::lock_guard lock(mutex_);
  for (std::size_t r = 1; r < timings_.ranks.size(); ++r) timings_.ranks[r].state = state;
}

void ClusterFrames::endJob(const std::exception& error) {
  log_ << "holotraced: rank 0 of " << comm_.size() << ": error in a distributed frame: " << error.what()
       << "; ending every rank" << std::endl;
  comm_.abort(1);
  std::_Exit(1);  // abort() does not return (the compiler cannot see that through the virtual call)
}

ClusterTimings ClusterFrames::timings() const {
  std::lock_guard lock(mutex_);
  return timings_;
}

void ClusterFrames::stop() {
  if (stopped_) return;
  stopped_ = true;
  ClusterJob stop;
  stop.kind = ClusterJob::Kind::Stop;
  try {
    std::uint64_t bytes = 0;
    announce(stop, bytes);
  } catch (const std::exception& e) { endJob(e); }
}

}  // namespace ht::server
