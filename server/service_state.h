// service_state.h - what the RPC handlers share: registries, the render worker, the file sinks, limits, and the
// shutdown signal that stream handlers watch.
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <mutex>

#include "server/call_watchdog.h"
#include "server/daemon_config.h"
#include "server/display_registry.h"
#include "server/file_sink.h"
#include "server/progressive_streams.h"
#include "server/render_worker.h"
#include "server/scene_library.h"
#include "server/upload_budget.h"

namespace ht::server {

class PanelSinks;
class DistributedFrames;

struct ServiceState {
  const DaemonConfig& config;
  DisplayRegistry& displays;
  SceneLibrary& scenes;
  RenderWorker& worker;
  FileSink& outputSink;
  UploadBudget& uploads;
  CallWatchdog& watchdog;                // cancels stalled uploads and streams
  ProgressiveStreams& progressive;       // accumulations of progressive StreamFrames calls
  PanelSinks* panels = nullptr;          // display sinks of the config's "present" (server/panel_sinks.h); null = none
  DistributedFrames* cluster = nullptr;  // under mpirun: frames made by every rank (server/distributed_frames.h)

  std::atomic<std::uint32_t> activeStreams{0};
  std::atomic<std::uint64_t> nextFrameId{1};

  // Shutdown: stream handlers stop at the next frame boundary.
  std::mutex shutdownMutex;
  std::condition_variable shutdownCv;
  std::atomic<bool> shuttingDown{false};

  void beginShutdown() {
    {
      std::lock_guard lock(shutdownMutex);
      shuttingDown = true;
    }
    shutdownCv.notify_all();
  }
  // Sleeps until `deadline` or shutdown; returns false on shutdown.
  bool sleepUntil(std::chrono::steady_clock::time_point deadline) {
    std::unique_lock lock(shutdownMutex);
    return !shutdownCv.wait_until(lock, deadline, [this] { return shuttingDown.load(); });
  }
};

// Holds one of limits.max_clients streaming-call slots for its lifetime; throws LimitExceeded when none is free.
class StreamSlot {
 public:
  explicit StreamSlot(ServiceState& state);
  ~StreamSlot();
  StreamSlot(const StreamSlot&) = delete;
  StreamSlot& operator=(const StreamSlot&) = delete;

 private:
  ServiceState& state_;
};

}  // namespace ht::server
