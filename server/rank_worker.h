// rank_worker.h - a rank > 0 of holotraced under mpirun (docs/CLUSTER.md §8): no gRPC, no socket; it waits for rank
// 0's frame jobs (server/cluster_job.h), keeps the scene versions rank 0 sends (each with its own BVH, on its own
// Vulkan device), renders the work units rank 0 hands it, and returns when rank 0 says stop.
#pragma once
#include <ostream>

#include "cluster/communicator.h"
#include "server/daemon_config.h"

namespace ht::server {

// How long a rank that got SIGTERM/SIGINT waits for rank 0's stop before it ends the job itself: mpirun forwards a
// signal to every rank, and rank 0 then stops the others cleanly; a signal to this rank alone ends the job.
inline constexpr double kStopWaitSeconds = 15.0;  // > rank 0's drain: 5 s of stream grace + a frame

// Serves until rank 0's stop (returns) or fails (throws; the caller ends the job on every rank). Signals SIGTERM,
// SIGINT and SIGHUP must be blocked in the calling thread (they are polled).
void runWorkerRank(cluster::Communicator& comm, const DaemonConfig& config, std::ostream& log);

}  // namespace ht::server
