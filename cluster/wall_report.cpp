// wall_report.cpp - see wall_report.h.
#include "cluster/wall_report.h"

#include <algorithm>
#include <cstring>

#include "cluster/cluster_error.h"

namespace ht::cluster {
namespace {

WallRankSummary summarizeRank(std::span<const WallFrameRecord> frames) {
  WallRankSummary s;
  std::vector<double> render, wait, present;
  for (const WallFrameRecord& r : frames) {
    s.onTime += r.outcome == WallOutcome::OnTime;
    s.timedOut += r.outcome == WallOutcome::TimedOut;
    s.late += r.outcome == WallOutcome::Late || r.outcome == WallOutcome::LateShown;
    s.presented += r.outcome == WallOutcome::LateShown;
    s.skipped += r.outcome == WallOutcome::Skipped;
    if (r.renderUs >= 0) render.push_back(double(r.renderUs) / 1000.0);
    if (r.renderUs >= 0 && r.releaseUs >= 0) wait.push_back(double(r.releaseUs - r.entryUs) / 1000.0);
    if (r.presentUs >= 0) present.push_back(double(r.presentUs) / 1000.0);
  }
  s.presented += s.onTime + s.timedOut;
  for (double v : render) s.renderTotalMs += v;
  for (double v : wait) s.waitTotalMs += v;
  for (double v : present) s.presentTotalMs += v;
  s.renderMedianMs = medianOf(render);
  s.waitMedianMs = medianOf(wait);
  s.presentMedianMs = medianOf(present);
  return s;
}

}  // namespace

double medianOf(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2.0;
}

std::vector<WallFrameRecord> gatherWallRecords(Communicator& comm, std::span<const WallFrameRecord> mine) {
  const auto bytes = comm.allGather(
      std::span(reinterpret_cast<const std::uint8_t*>(mine.data()), mine.size() * sizeof(WallFrameRecord)));
  std::vector<WallFrameRecord> all(bytes.size() / sizeof(WallFrameRecord));
  if (!all.empty()) std::memcpy(all.data(), bytes.data(), all.size() * sizeof(WallFrameRecord));
  return all;
}

WallSummary summarizeWall(std::span<const WallFrameRecord> all, int ranks) {
  if (ranks <= 0 || all.size() % std::size_t(ranks) != 0) {
    throw ClusterError("wall report: " + std::to_string(all.size()) + " frame records do not split over " +
                       std::to_string(ranks) + " ranks");
  }
  WallSummary s;
  s.frames = static_cast<std::uint32_t>(all.size() / std::size_t(ranks));
  const auto rankFrames = [&](int r) { return all.subspan(std::size_t(r) * s.frames, s.frames); };
  for (int r = 0; r < ranks; ++r) {
    s.ranks.push_back(summarizeRank(rankFrames(r)));
    for (std::uint32_t f = 0; f < s.frames; ++f) {
      const WallFrameRecord& rec = rankFrames(r)[f];
      if (rec.outcome == WallOutcome::Late || rec.outcome == WallOutcome::LateShown)
        s.late.push_back({r, f, double(rec.lateByUs) / 1000.0});
    }
  }
  std::vector<double> cost, release, flip;
  for (std::uint32_t f = 0; f < s.frames; ++f) {
    bool synced = true;
    std::int64_t lastEntry = -1, lastWait = 0, relMin = 0, relMax = 0, flipMin = 0, flipMax = 0;
    for (int r = 0; r < ranks && synced; ++r) {
      const WallFrameRecord& rec = rankFrames(r)[f];
      synced = rec.outcome == WallOutcome::OnTime && rec.flipUs >= 0;
      if (!synced) break;
      if (rec.entryUs > lastEntry) lastEntry = rec.entryUs, lastWait = rec.releaseUs - rec.entryUs;
      relMin = r == 0 ? rec.releaseUs : std::min(relMin, rec.releaseUs);
      relMax = r == 0 ? rec.releaseUs : std::max(relMax, rec.releaseUs);
      flipMin = r == 0 ? rec.flipUs : std::min(flipMin, rec.flipUs);
      flipMax = r == 0 ? rec.flipUs : std::max(flipMax, rec.flipUs);
    }
    if (!synced) continue;
    ++s.syncedFrames;
    cost.push_back(double(lastWait));
    release.push_back(double(relMax - relMin));
    flip.push_back(double(flipMax - flipMin));
  }
  s.barrierCostMedianUs = medianOf(cost);
  s.releaseSkewMedianUs = medianOf(release);
  s.flipSkewMedianUs = medianOf(flip);
  s.flipSkewMaxUs = flip.empty() ? 0.0 : *std::max_element(flip.begin(), flip.end());
  return s;
}

}  // namespace ht::cluster
