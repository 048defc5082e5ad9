// load_rss_series.cpp - see load_rss_series.h.
#include "bench/load_rss_series.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace ht::bench {

double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  if (x.size() < 2) return 0.0;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i] / n, my += y[i] / n;
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  return sxx > 0 ? sxy / sxx : 0.0;
}

void writeSamplesCsv(const std::vector<DaemonSample>& samples, const std::string& file) {
  std::ofstream out(file);
  out << "seconds,frames,rss_kib,cpu_seconds,threads\n";
  for (const DaemonSample& s : samples) {
    out << s.seconds << ',' << s.frames << ',' << s.rssKiB << ',' << s.cpuSeconds << ',' << s.threads << '\n';
  }
  if (!out.flush()) throw std::runtime_error("cannot write " + file);
}

RssSummary summarizeRss(const std::vector<DaemonSample>& samples, std::uint64_t fromFrames) {
  RssSummary s;
  std::vector<double> frames, rss;
  for (const DaemonSample& sample : samples) {
    if (sample.frames < fromFrames) continue;
    if (rss.empty()) s.firstKiB = sample.rssKiB;
    s.lastKiB = sample.rssKiB;
    s.maxKiB = std::max(s.maxKiB, sample.rssKiB);
    frames.push_back(static_cast<double>(sample.frames));
    rss.push_back(static_cast<double>(sample.rssKiB));
  }
  s.samplesUsed = rss.size();
  s.slopeKiBPer1000Frames = 1000.0 * leastSquaresSlope(frames, rss);
  return s;
}

}  // namespace ht::bench
