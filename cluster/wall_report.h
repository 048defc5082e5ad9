// wall_report.h - what a live wall run measured (docs/CLUSTER.md §7): every rank's frame records (wall_loop.h),
// gathered to every rank, summarised per rank (render, barrier wait, present), per frame (the swap barrier's cost
// and the flip skew between ranks) and as the list of late ranks. Pure functions of the records.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "cluster/communicator.h"
#include "cluster/wall_loop.h"

namespace ht::cluster {

// Every rank's records, rank after rank (the same frame count on every rank). Collective: call it on every rank.
std::vector<WallFrameRecord> gatherWallRecords(Communicator& comm, std::span<const WallFrameRecord> mine);

struct WallRankSummary {
  std::uint32_t presented = 0, onTime = 0, timedOut = 0, late = 0, skipped = 0;
  double renderMedianMs = 0.0, waitMedianMs = 0.0, presentMedianMs = 0.0;  // over the frames it rendered / showed
  double renderTotalMs = 0.0, waitTotalMs = 0.0, presentTotalMs = 0.0;
};

struct WallLateEvent {
  int rank = 0;
  std::uint32_t frame = 0;
  double lateByMs = 0.0;  // its entry after the first rank's entry + deadline
};

struct WallSummary {
  std::uint32_t frames = 0;
  std::vector<WallRankSummary> ranks;
  std::vector<WallLateEvent> late;  // frames a rank rendered after the others' deadline (Late, LateShown)
  std::uint32_t syncedFrames = 0;   // frames every rank presented on time: the ones the figures below use
  // Barrier cost: the wait of the last rank to enter (the others were there already), median over synced frames.
  double barrierCostMedianUs = 0.0;
  // Spread of the barrier's release and of the flips (present issued) over the ranks, per synced frame.
  double releaseSkewMedianUs = 0.0, flipSkewMedianUs = 0.0, flipSkewMaxUs = 0.0;
};

WallSummary summarizeWall(std::span<const WallFrameRecord> all, int ranks);

double medianOf(std::vector<double> values);  // 0 for none

}  // namespace ht::cluster
