// daemon.h - holotraced's parts wired together: Vulkan device + render worker, displays, scenes, file sinks, the
// gRPC server (holotrace.v1, grpc.health.v1, reflection v1alpha) on its listen addresses.
#pragma once
#include <chrono>
#include <memory>
#include <ostream>

#include "server/daemon_config.h"

namespace ht::server {

class Daemon {
 public:
  Daemon(DaemonConfig config, std::ostream& log);  // opens the device and roots; throws ht::Error
  ~Daemon();                                       // shutdown() if still running
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
