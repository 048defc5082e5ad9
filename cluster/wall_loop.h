// wall_loop.h - the frame loop of a live wall (docs/CLUSTER.md §7): every rank renders its own projectors' views of
// frame f, enters the swap barrier (swap_barrier.h), and presents when every rank entered or its deadline passed:
//
//   render f -> swap barrier (polled until all ranks entered, at most `deadlineUs`) -> present f -> frame f + 1
//
// - On time: the barrier completes before the deadline; every rank presents f.
// - Timed out: this rank waited `deadlineUs` and presents f without the rank(s) not yet there (warned, recorded).
// - Late: this rank entered after the first rank's entry + `deadlineUs`, so the others have flipped without it; it
//   does not present its stale frame and catches up: it enters the next frames' barriers without rendering them
//   (Skipped) as long as those complete at once and it is late for them too, then renders the next frame. The run's
//   last frame is never skipped and always shown, late or not (LateShown).
// - Repeated misses: `maxMissed` (> 0) consecutive timed-out frames end the job with a ClusterError; 0 never does.
// - The end: --frames N: every rank renders and presents frame N - 1 (a late rank never skips the last frame);
//   --seconds T: each rank stops when the job clock passes T, the ranks agree on the furthest frame reached, the
//   others enter the barriers up to it, and every rank renders and presents one more, common last frame.
//
// The loop itself renders and presents nothing: the caller's callbacks do (cli/wall_command.cpp; tests).
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cluster/communicator.h"
#include "cluster/swap_barrier.h"

namespace ht::cluster {

enum class WallOutcome : std::int32_t {
  Missing = 0,    // no record (not reached)
  OnTime = 1,     // presented after every rank entered the barrier
  TimedOut = 2,   // presented at this rank's deadline, without the rank(s) not yet there
  Late = 3,       // rendered, but entered after the others' deadline: not presented
  Skipped = 4,    // entered without rendering, to catch up with the others
  LateShown = 5,  // late, but the run's last frame: shown anyway, so every rank ends on the same frame
};
const char* wallOutcomeName(WallOutcome outcome);

// One rank's frame, times on the job clock in microseconds (-1: did not happen). Fixed size: gathered as bytes.
struct WallFrameRecord {
  std::int64_t renderUs = -1;   // duration of the render callback
  std::int64_t entryUs = -1;    // when this rank entered the swap barrier
  std::int64_t releaseUs = -1;  // when it stopped waiting (the barrier completed or its deadline passed)
  std::int64_t flipUs = -1;     // when its present was issued to the display (returned by the present callback)
  std::int64_t presentUs = -1;  // duration of the present callback
  std::int64_t firstEntryUs = -1, lastEntryUs = -1;  // of all ranks, from the completed barrier
  std::int64_t lateByUs = 0;                         // Late / Skipped: entry - (first entry + deadline)
  WallOutcome outcome = WallOutcome::Missing;
  std::int32_t reserved = 0;
};

struct WallLoopOptions {
  std::optional<std::uint32_t> frames;  // --frames N, or
  std::optional<double> seconds;        // --seconds T (at least one frame)
  std::int64_t deadlineUs = 100000;     // how long a rank waits at the swap barrier
  std::uint32_t maxMissed = 0;          // consecutive timed-out frames that end the job; 0 = never
};

struct WallCallbacks {
  std::function<void(std::uint32_t frame)> render;  // renders this rank's views of `frame`
  // Presents the frame rendered last; returns when the present was issued (job clock, microseconds).
  std::function<std::int64_t(std::uint32_t frame)> present;
  std::function<void(const std::string& line)> warn;  // one line per timed-out or late frame
};

// Runs the loop on this rank; `clock` is synchronised with rank 0's at the start (synchronizeJobClock). Returns one
// record per frame of the run (the same count on every rank).
std::vector<WallFrameRecord> runWallLoop(Communicator& comm, const WallLoopOptions& options,
                                         const WallCallbacks& callbacks, JobClock& clock);

}  // namespace ht::cluster
