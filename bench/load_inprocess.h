// load_inprocess.h - the load run's baseline: the same frames (display, scene, spp, pixel encoding) rendered and
// encoded in this process through the daemon's own code path (RenderWorker + renderFrameJob + encodeFrame), with no
// gRPC. Its CPU time per frame, against the daemon's, is the CPU cost of the protocol.
#pragma once
#include <cstdint>
#include <string>

namespace ht::bench {

struct InProcessRun {
  std::uint64_t frames = 0;
  double wallSeconds = 0.0;
  double cpuSeconds = 0.0;  // this process, user + system, all threads (lavapipe's included)
};

// `displaysDir` may be empty (builtin displays only); `scene` is "builtin:NAME" or a file path.
InProcessRun renderInProcess(const std::string& displaysDir, const std::string& display, const std::string& scene,
                             std::uint32_t spp, std::uint64_t frames);

}  // namespace ht::bench
