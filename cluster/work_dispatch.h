// work_dispatch.h - rank 0 hands out work units and collects their pixels (docs/CLUSTER.md §3).
//
// Dynamic (default): every other rank asks rank 0 for a unit, renders it, sends its pixels back (which asks for the
// next) until rank 0 answers "stop"; views and bands do not cost the same, so fast ranks simply take more. Rank 0
// renders units too, on a second thread, while its main thread (the only one calling MPI) answers requests and
// receives pixels. Static (for comparison): rank r renders the r-th contiguous block of the unit list.
// Results reach `sink` on rank 0's main thread, in arrival order; placing them by unit index keeps the output
// independent of that order. Any exception on any thread propagates out of dispatchWork on that rank (the caller
// aborts the job: a peer blocked in MPI cannot be woken otherwise).
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "cluster/communicator.h"
#include "cluster/work_plan.h"

namespace ht::cluster {

enum class Assignment { Dynamic, Static };

// Renders a unit; returns its RGBA floats, or nothing when the rank wrote the unit's files itself.
using UnitRenderer = std::function<std::vector<float>(const WorkUnit&)>;
// Rank 0: unit `unit` is done, with its pixels (empty when its rank wrote it).
using UnitSink = std::function<void(std::size_t unit, std::vector<float>&& rgba)>;

struct RankWork {
  std::uint32_t units = 0;
  double busyMs = 0.0;  // inside UnitRenderer
};

struct DispatchReport {
  double wallMs = 0.0;            // of dispatchWork on this rank
  std::vector<RankWork> ranks;    // rank 0: every rank's; other ranks: their own at their index
  std::uint64_t gatherBytes = 0;  // rank 0: pixel bytes received from other ranks
  double gatherMs = 0.0;          // rank 0: time spent receiving them (after their header arrived)
};

// Environment variable of the failure test: rank N kills itself (SIGKILL) after rendering its first unit, before
// sending it, to check that the job ends on every rank without output (tests/cluster).
inline constexpr const char* kKillRankVariable = "HOLOTRACE_TEST_KILL_RANK";

DispatchReport dispatchWork(Communicator& comm, std::span<const WorkUnit> units, const UnitRenderer& render,
                            const UnitSink& sink, Assignment assignment = Assignment::Dynamic);

}  // namespace ht::cluster
