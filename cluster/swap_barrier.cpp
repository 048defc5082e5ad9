// swap_barrier.cpp - see swap_barrier.h. The barrier is a max-reduction of (entry, -entry): its result holds the
// last entry and the negated first one.
//
// Polling: a non-blocking collective progresses only inside MPI calls on every rank, so a waiting rank tests it
// again every few microseconds. Measured on 2 cores with 2 ranks (docs/BENCHMARKS.md "Live wall"): sleeping 20 us
// between tests with the default 50 us timer slack made the last rank's wait ~240 us; spinning with yield made it
// ~50 us but takes a core from ranks still rendering (3 ranks on 2 cores). So the polling thread sleeps 10 us with a
// 1 us timer slack (prctl PR_SET_TIMERSLACK): ~80-130 us, cheap for the cores.
#include "cluster/swap_barrier.h"

#include <sys/prctl.h>

#include <array>
#include <string>
#include <thread>

#include "cluster/cluster_error.h"

namespace ht::cluster {
namespace {

constexpr std::chrono::microseconds kPollSleep{10};
constexpr int kClockTag = 7100;  // the clock exchange's messages (the wall uses no other point-to-point tag)

void pollSleep() {
  static thread_local const bool slackSet = prctl(PR_SET_TIMERSLACK, 1000UL, 0, 0, 0) == 0;  // 1 us, this thread
  (void)slackSet;
  std::this_thread::sleep_for(kPollSleep);
}

}  // namespace
void synchronizeJobClock(Communicator& comm, JobClock& clock, int rounds) {
  using SteadyClock = std::chrono::steady_clock;
  comm.barrier();
  if (comm.rank() == 0) {
    clock.restart();
    for (int r = 1; r < comm.size(); ++r) {
      for (int k = 0; k < rounds; ++k) {
        (void)receiveRecord<std::uint8_t>(comm, r, kClockTag);
        sendRecord(comm, r, kClockTag, clock.nowUs());
      }
    }
  } else {
    auto best = SteadyClock::duration::max();
    for (int k = 0; k < rounds; ++k) {
      const auto sent = SteadyClock::now();
      sendRecord(comm, 0, kClockTag, std::uint8_t{1});
      const auto rootUs = receiveRecord<std::int64_t>(comm, 0, kClockTag);
      const auto back = SteadyClock::now();
      if (back - sent >= best) continue;
      best = back - sent;
      clock.setEpoch(sent + (back - sent) / 2 - std::chrono::microseconds(rootUs));
    }
  }
  comm.barrier();
}

void SwapBarrier::enter(std::uint32_t frame, std::int64_t entryUs) {
  if (frame != entered_) {
    throw ClusterError("swap barrier: frame " + std::to_string(frame) + " entered after frame " +
                       std::to_string(entered_) + " was due (frames must be entered in order, none left out)");
  }
  const std::array<std::int64_t, 2> values = {entryUs, -entryUs};
  pending_.emplace(frame, comm_.startMaxReduction(values));
  ++entered_;
}

void SwapBarrier::poll() {
  for (auto it = pending_.begin(); it != pending_.end();) {
    if (!it->second->test()) {
      ++it;
      continue;
    }
    const std::vector<std::int64_t>& r = it->second->result();
    done_[it->first] = SwapEntries{-r[1], r[0]};
    it = pending_.erase(it);
  }
}

std::optional<SwapEntries> SwapBarrier::waitUntil(std::uint32_t frame, std::int64_t untilUs, const JobClock& clock) {
  while (true) {
    poll();
    if (auto r = result(frame)) return r;
    if (clock.nowUs() >= untilUs) return std::nullopt;
    pollSleep();
  }
}

void SwapBarrier::finish() {
  while (true) {
    poll();
    if (pending_.empty()) return;
    pollSleep();
  }
}

std::optional<SwapEntries> SwapBarrier::result(std::uint32_t frame) const {
  const auto it = done_.find(frame);
  if (it == done_.end()) return std::nullopt;
  return it->second;
}

}  // namespace ht::cluster
