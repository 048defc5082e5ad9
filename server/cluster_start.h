// cluster_start.h - the start of holotraced under mpirun, on every rank (docs/CLUSTER.md §8): the ranks check that
// they run the same build, the same display configs and the same daemon config file (cluster/rank_identity.h: one
// exchange; a mismatch stops every rank with the same message before any device is opened), and learn each other's
// host name and process id (for Status).
#pragma once
#include <ostream>
#include <vector>

#include "cluster/communicator.h"
#include "server/cluster_frames.h"
#include "server/daemon_config.h"

namespace ht::server {

// Throws cluster::RankMismatchError on every rank when any rank differs from rank 0.
std::vector<RankInfo> startCluster(cluster::Communicator& comm, const DaemonConfig& config);

}  // namespace ht::server
