// timing_series.h - the per-run times of one tracer and their median; the median of any per-run values (ratios).
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace ht::bench {

// Median of the values (the mean of the middle two for an even count); 0 for none.
inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

struct TimingSeries {
  std::vector<double> ms;  // one entry per timed run, in run order

  double medianMs() const { return median(ms); }
  double medianMraysPerSecond(std::uint64_t rays) const {
    const double median = medianMs();
    return median > 0.0 ? double(rays) / (median * 1e3) : 0.0;
  }
};

}  // namespace ht::bench
