// load_rss_series.h - the daemon's RSS and CPU time sampled during a load run, and the figures that say whether
// memory stays flat: first / last / max RSS and the least-squares slope of RSS over delivered frames.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace ht::bench {

struct DaemonSample {
  double seconds = 0.0;      // since the run started
  std::uint64_t frames = 0;  // delivered to the load clients so far
  std::uint64_t rssKiB = 0;
  double cpuSeconds = 0.0;  // daemon user + system
  std::uint32_t threads = 0;
};

struct RssSummary {
  std::uint64_t firstKiB = 0, lastKiB = 0, maxKiB = 0;
  double slopeKiBPer1000Frames = 0.0;  // least squares over the samples used
  std::size_t samplesUsed = 0;
};

// Summarises the samples taken at or after `fromFrames` delivered frames (skips warm-up: gRPC arenas, the
// renderer's per-size buffers and allocator pools grow during the first frames by design).
RssSummary summarizeRss(const std::vector<DaemonSample>& samples, std::uint64_t fromFrames);

// One line per sample: seconds,frames,rss_kib,cpu_seconds,threads (with a header line). Throws on I/O failure.
void writeSamplesCsv(const std::vector<DaemonSample>& samples, const std::string& file);

// Least-squares slope of y over x; 0 for fewer than two distinct x.
double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace ht::bench
