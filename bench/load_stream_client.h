// load_stream_client.h - one simulated holotraced client: StreamFrames on its own connection, counting complete
// frames into shared totals; optionally re-opens the call every N frames (exercises per-call setup/teardown).
#pragma once
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "holotrace/v1/holotrace.pb.h"

namespace ht::bench {

struct LoadTotals {
  std::atomic<std::uint64_t> frames{0};
  std::atomic<std::uint64_t> calls{0};
  std::mutex mutex;               // guards the fields below
  std::vector<double> latencyMs;  // queue_ms + render_ms of each frame
  std::uint64_t dropped = 0, bytes = 0, failedCalls = 0;
  std::string lastError;
};

struct LoadStop {
  std::chrono::steady_clock::time_point end;
  std::uint64_t frames = 0;  // total over all clients; 0 = no frame limit
  bool reached(const LoadTotals& totals) const;
};

void runStreamClient(const std::string& address, const holotrace::v1::StreamRequest& request, const LoadStop& stop,
                     std::uint64_t reconnectEvery, LoadTotals& totals);

}  // namespace ht::bench
