// communicator_none.cpp - Communicator::join() of a build without MPI (HOLOTRACE_WITH_MPI off or not found).
#include "cluster/cluster_error.h"
#include "cluster/communicator.h"

namespace ht::cluster {

std::unique_ptr<Communicator> Communicator::join(ThreadUse) {
  throw ClusterError(
      "this holotrace was built without MPI (configure with -DHOLOTRACE_WITH_MPI=ON and Open MPI installed: "
      "apt-get install libopenmpi-dev openmpi-bin); run it without mpirun to render in one process");
}

}  // namespace ht::cluster
