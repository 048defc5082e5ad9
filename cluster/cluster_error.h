// cluster_error.h - the errors of a render spread over MPI ranks (docs/CLUSTER.md).
#pragma once
#include <string>

#include "common/error.h"

namespace ht::cluster {

// An MPI call failed (the message names the call and MPI's own error string), the job was launched in a way this
// build cannot serve (mpirun without MPI support), or a peer sent something unexpected.
class ClusterError : public Error {
 public:
  using Error::Error;
};

// The ranks of one job disagree on what they run (build, display, scene or render settings): every rank throws it
// after the start-up check, so the whole job stops with the same message before any work (rank_identity.h).
class RankMismatchError : public ClusterError {
 public:
  using ClusterError::ClusterError;
};

}  // namespace ht::cluster
