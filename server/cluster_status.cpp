// cluster_status.cpp - see cluster_status.h.
#include "server/cluster_status.h"

#include "server/distributed_frames.h"
#include "server/service_state.h"

namespace ht::server {

void addClusterStatus(const ServiceState& state, holotrace::v1::StatusResponse& response) {
  if (state.cluster == nullptr) return;
  const ClusterTimings t = state.cluster->timings();
  for (const RankTimings& r : t.ranks) {
    holotrace::v1::RankStatus& out = *response.add_ranks();
    out.set_rank(r.rank);
    out.set_host(r.host);
    out.set_pid(r.pid);
    out.set_state(r.state);
    out.set_last_busy_ms(r.lastBusyMs);
    out.set_last_units(r.lastUnits);
    out.set_last_idle_ms(r.lastIdleMs);
    out.set_total_busy_ms(r.totalBusyMs);
    out.set_total_units(r.totalUnits);
  }
  holotrace::v1::ClusterFrameStatus& c = *response.mutable_cluster();
  c.set_frames(t.frames);
  c.set_last_frame_ms(t.lastFrameMs);
  c.set_last_broadcast_ms(t.lastBroadcastMs);
  c.set_last_broadcast_bytes(t.lastBroadcastBytes);
  c.set_last_gather_ms(t.lastGatherMs);
  c.set_last_gather_bytes(t.lastGatherBytes);
  c.set_scene_broadcasts(t.sceneBroadcasts);
  c.set_work_units(t.workUnits);
}

}  // namespace ht::server
