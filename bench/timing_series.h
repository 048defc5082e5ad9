// timing_series.h - the per-run times of one tracer and their median.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace ht::bench {

struct TimingSeries {
  std::vector<double> ms;  // one entry per timed run, in run order

  double medianMs() const {
    if (ms.empty()) return 0.0;
    std::vector<double> sorted = ms;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    return n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  }
  double medianMraysPerSecond(std::uint64_t rays) const {
    const double median = medianMs();
    return median > 0.0 ? double(rays) / (median * 1e3) : 0.0;
  }
};

}  // namespace ht::bench
