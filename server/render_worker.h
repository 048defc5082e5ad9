// render_worker.h - the one thread that talks to a Vulkan device. A Renderer is not thread-safe, so every GPU job
// (BVH upload, frame) runs here, one at a time. Jobs are queued per client and taken round-robin across clients,
// so one client streaming at full rate cannot starve another; each client may have at most `maxInFlight` jobs
// queued or running (LimitExceeded beyond that, before anything is allocated).
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <list>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "gpu/vulkan_context.h"
#include "server/errors.h"

namespace ht::server {

struct WorkerStats {
  std::string deviceName;
  std::uint64_t framesRendered = 0;
  double lastFrameMs = 0.0;
  double meanFrameMs = 0.0;
  std::uint32_t queued = 0;
};

class RenderWorker {
 public:
  using Job = std::function<void(gpu::VulkanContext&)>;

  RenderWorker(gpu::VulkanContext& context, std::uint32_t maxInFlightPerClient);
  ~RenderWorker();  // stop()
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  // Queues `job` for `client`; the future carries its exception. Throws LimitExceeded or ShuttingDown.
  // `countsAsFrame` jobs update the frame statistics.
  std::future<void> submit(const std::string& client, Job job, bool countsAsFrame = true);

  // Runs `release` on the worker thread, before its next job, without waiting (GPU objects whose destruction
  // touches the device's shared pools: an evicted scene's Renderer). Runs it at once when called on the worker
  // thread or after the worker stopped.
  void dispose(std::function<void()> release);

  // Fails queued jobs with ShuttingDown, lets the running one finish, joins the thread. Idempotent.
  void stop();
  WorkerStats stats() const;

 private:
  struct Task {
    Job job;
    std::promise<void> done;
    bool countsAsFrame = true;
  };
  void run();
  bool takeNext(Task& task, std::string& client);
  void finish(const std::string& client, double ms, bool countsAsFrame);

  gpu::VulkanContext& context_;
  const std::uint32_t maxInFlight_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::map<std::string, std::deque<Task>> queues_;
  std::list<std::string> roundRobin_;              // clients with queued tasks, next first
  std::map<std::string, std::uint32_t> inFlight_;  // queued + running, per client
  bool stopping_ = false;
  bool finished_ = false;  // the thread ran its last disposal
  std::vector<std::function<void()>> disposals_;
  WorkerStats stats_;
  double totalFrameMs_ = 0.0;
  std::thread thread_;
};

}  // namespace ht::server
