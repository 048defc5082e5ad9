// daemon.h - holotraced's parts wired together: Vulkan device + render worker, displays, scenes, file sinks, the
// gRPC server (holotrace.v1, grpc.health.v1, reflection v1alpha) on its listen addresses.
#pragma once
#include <chrono>
#include <memory>
#include <ostream>

#include "server/daemon_config.h"
#include "server/distributed_frames.h"

namespace ht::server {

class Daemon {
 public:
  // Opens the device and roots; throws ht::Error. `cluster`: rank 0 of an MPI job (docs/CLUSTER.md §8): frames are
  // rendered by every rank through it, and shutdown() stops the other ranks after the render worker.
  Daemon(DaemonConfig config, std::ostream& log, std::unique_ptr<DistributedFrames> cluster = nullptr);
  ~Daemon();  // shutdown() if still running
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  void start();  // binds every listen address; throws IoError if one fails
  // Stops accepting, lets in-flight calls end at their next frame boundary (cancelled after `grace`), stops the
  // render worker. Idempotent.
  void shutdown(std::chrono::milliseconds grace = std::chrono::seconds(5));
  std::size_t reloadDisplays();  // SIGHUP: displays re-read, panel sinks added / removed to match (docs/SERVICE.md §11)

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

}  // namespace ht::server
