// mpi_launch.h - whether this process was started by an MPI launcher (mpirun / mpiexec, or srun with PMIx), read
// from the environment the launcher sets, without initialising MPI: a plain `holotrace render` never touches MPI.
#pragma once
#include <optional>

namespace ht::cluster {

// The world size the launcher announced (OMPI_COMM_WORLD_SIZE, PMIX_SIZE... see mpi_launch.cpp), or nullopt when
// the process was not started by an MPI launcher.
std::optional<int> launcherWorldSize();

// True when this build can join an MPI job (HOLOTRACE_WITH_MPI found Open MPI at configure time).
bool builtWithMpi();

}  // namespace ht::cluster
