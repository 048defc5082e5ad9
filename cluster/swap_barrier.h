// swap_barrier.h - the live wall's swap barrier (docs/CLUSTER.md §7): every rank enters it for a frame once that
// frame is rendered, and presents when every rank has entered, or when its own deadline passed first. It is a
// non-blocking collective polled against the deadline, never a blocking wait, so a rank that falls behind delays the
// others by at most the deadline. Each entry carries the rank's entry time on the job clock; the completed barrier
// tells every rank the first and last entry of the frame, so a rank can tell that it came after the others' deadline
// (it was late, and they have flipped without it).
#pragma once
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>

#include "cluster/communicator.h"

namespace ht::cluster {

// Microseconds since the job's common start, on every rank: synchronizeJobClock() sets each rank's epoch to the local
// time at which rank 0's clock started, so the ranks' timestamps compare whatever the hosts' clocks say.
class JobClock {
 public:
  JobClock() : epoch_(std::chrono::steady_clock::now()) {}
  void restart() { epoch_ = std::chrono::steady_clock::now(); }
  void setEpoch(std::chrono::steady_clock::time_point epoch) { epoch_ = epoch; }
  std::int64_t nowUs() const { return toUs(std::chrono::steady_clock::now()); }
  std::int64_t toUs(std::chrono::steady_clock::time_point t) const {
    return std::chrono::duration_cast<std::chrono::microseconds>(t - epoch_).count();
  }

 private:
  std::chrono::steady_clock::time_point epoch_;
};

// Starts rank 0's clock and aligns every other rank's to it (Cristian's method: the round trip to rank 0 with the
// shortest time of `rounds` gives the offset to within half of it, microseconds over shared memory, so a rank the
// scheduler delayed in one exchange does not shift its clock). Collective; ends with a barrier. A plain barrier exit
// instead left the clocks up to 27 ms apart on the loaded 2-core test machine (docs/CLUSTER.md §7).
void synchronizeJobClock(Communicator& comm, JobClock& clock, int rounds = 16);

// What a completed swap barrier tells every rank about one frame.
struct SwapEntries {
  std::int64_t firstUs = 0;  // the earliest entry of any rank (job clock)
  std::int64_t lastUs = 0;   // the latest
};

class SwapBarrier {
 public:
  explicit SwapBarrier(Communicator& comm) : comm_(comm) {}

  // Enters the barrier of `frame` at `entryUs`. Every rank enters every frame once, in order 0, 1, 2, ... (a rank
  // that skips a frame still enters it, so the collectives of all ranks match).
  void enter(std::uint32_t frame, std::int64_t entryUs);
  // Polls the barrier of `frame` (and the older ones still pending) until it completes or `clock` passes `untilUs`.
  std::optional<SwapEntries> waitUntil(std::uint32_t frame, std::int64_t untilUs, const JobClock& clock);
  // Polls every pending barrier once.
  void poll();
  // Polls until every entered barrier has completed (the end of the run: every rank enters all of them).
  void finish();

  std::optional<SwapEntries> result(std::uint32_t frame) const;
  std::uint32_t entered() const { return entered_; }  // frames entered so far (the next frame to enter)
  std::size_t pending() const { return pending_.size(); }

 private:
  Communicator& comm_;
  std::uint32_t entered_ = 0;
  std::map<std::uint32_t, std::unique_ptr<PendingReduction>> pending_;
  std::map<std::uint32_t, SwapEntries> done_;
};

}  // namespace ht::cluster
