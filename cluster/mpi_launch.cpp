// mpi_launch.cpp - see mpi_launch.h.
#include "cluster/mpi_launch.h"

#include <cstdlib>
#include <string>

namespace ht::cluster {

std::optional<int> launcherWorldSize() {
  // Open MPI's mpirun (OMPI_COMM_WORLD_SIZE), PMIx launchers such as srun --mpi=pmix (PMIX_RANK with the size in
  // OMPI_COMM_WORLD_SIZE or PMI_SIZE), MPICH's Hydra (PMI_SIZE).
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* value = std::getenv(name)) {
      try {
        return std::stoi(value);
      } catch (const std::exception&) {
        return 1;  // set but unreadable: still a launched process
      }
    }
  }
  if (std::getenv("PMIX_RANK")) return 1;
  return std::nullopt;
}

bool builtWithMpi() {
#ifdef HT_WITH_MPI
  return true;
#else
  return false;
#endif
}

}  // namespace ht::cluster
