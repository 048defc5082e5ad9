// cluster_status.h - the ranks part of Status for holotraced under mpirun (proto RankStatus, ClusterFrameStatus).
#pragma once
#include "holotrace/v1/holotrace.pb.h"

namespace ht::server {

struct ServiceState;

// Adds one RankStatus per rank and the last distributed frame's costs; nothing for a single-process daemon.
void addClusterStatus(const ServiceState& state, holotrace::v1::StatusResponse& response);

}  // namespace ht::server
