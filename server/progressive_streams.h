// progressive_streams.h - the accumulations of progressive StreamFrames calls (docs/REUSE.md §1-§2,
// docs/SERVICE.md §4.1). Calls that stream the same scene session to the same display with the
// same request share one stream: one device accumulation (gpu/accumulator.h), the last frame, and the state a new
// caller starts from (a converged stream's frame is sent at once, with no GPU work). A stream's device memory is
// reserved against limits.max_accumulator_bytes when its first caller joins: over the limit, the call fails with
// LimitExceeded (RESOURCE_EXHAUSTED) naming the limit and the values, before anything is allocated. The last caller
// to leave releases the accumulation on the render worker.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "gpu/accumulator.h"
#include "gpu/renderer.h"
#include "server/render_worker.h"
#include "server/scene_library.h"

namespace ht::server {

struct ProgressiveStream {
  std::string key, sceneId, displayId;
  std::uint64_t bytes = 0;  // reserved device memory
  // One frame of the stream at a time; guards everything below.
  std::mutex frameMutex;
  std::shared_ptr<gpu::Accumulator> accumulator;  // used on the render worker only, released there
  std::shared_ptr<const SceneSession> session;    // what the last frame shows (identity: scene and camera version)
  std::shared_ptr<const gpu::RenderResult> last;  // the last frame (sum / n per target)
  std::uint64_t frameNumber = 0;                  // of `last`, 0 = none yet
  std::uint32_t clients = 0;                      // guarded by the registry's mutex
  // What Status shows, guarded by statusMutex (a frame in progress holds frameMutex for its whole render).
  std::mutex statusMutex;
  gpu::AccumulationReport report;
  std::uint64_t framesRendered = 0;

  // After a frame that added samples (call with frameMutex held).
  void recordFrame(std::shared_ptr<const gpu::RenderResult> frame, std::shared_ptr<const SceneSession> shown);
};

struct StreamStatusEntry {
  std::string sceneId, displayId;
  gpu::AccumulationReport report;
  std::uint32_t clients = 0;
  std::uint64_t framesRendered = 0, bytes = 0;
};

class ProgressiveStreams {
 public:
  ProgressiveStreams(RenderWorker& worker, std::uint64_t limitBytes) : worker_(worker), limitBytes_(limitBytes) {}
  ~ProgressiveStreams();

  // Joins (or opens) the stream `key`; `bytes` is the device memory a new accumulation needs. Throws LimitExceeded
  // when opening it would put the streams over the limit.
  std::shared_ptr<ProgressiveStream> join(const std::string& key, const std::string& sceneId,
                                          const std::string& displayId, std::uint64_t bytes,
                                          const gpu::AccumulationPolicy& policy);
  void leave(const std::shared_ptr<ProgressiveStream>& stream);

  std::vector<StreamStatusEntry> status() const;
  std::uint64_t bytesInUse() const;
  std::uint64_t limitBytes() const { return limitBytes_; }

  // Holds a caller's membership for its lifetime.
  class Membership {
   public:
    Membership(ProgressiveStreams& streams, std::shared_ptr<ProgressiveStream> stream)
        : streams_(streams), stream_(std::move(stream)) {}
    ~Membership() { streams_.leave(stream_); }
    Membership(const Membership&) = delete;
    Membership& operator=(const Membership&) = delete;
    ProgressiveStream& stream() { return *stream_; }

   private:
    ProgressiveStreams& streams_;
    std::shared_ptr<ProgressiveStream> stream_;
  };

 private:
  RenderWorker& worker_;
  const std::uint64_t limitBytes_;
  mutable std::mutex mutex_;
  std::map<std::string, std::shared_ptr<ProgressiveStream>> streams_;
  std::uint64_t bytesInUse_ = 0;
};

}  // namespace ht::server
