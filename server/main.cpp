// main.cpp - holotraced --config FILE. Signals are taken synchronously with sigwait() on the main thread (blocked
// in every thread first): SIGTERM/SIGINT -> graceful shutdown, exit 0; SIGHUP -> reload display configs. SIGXFSZ is
// ignored, so a file-size limit fails one Capture instead of killing the daemon.
// Launched by mpirun (docs/CLUSTER.md §8), rank 0 is that daemon and renders every frame with the other ranks, which
// run a render loop (server/rank_worker.h); an error on any rank ends every rank (MPI_Abort) with a message.

#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <iostream>
#include <memory>
#include <string>

#include "cluster/cluster_error.h"
#include "cluster/communicator.h"
#include "cluster/mpi_launch.h"
#include "common/error.h"
#include "server/cluster_frames.h"
#include "server/cluster_start.h"
#include "server/daemon.h"
#include "server/daemon_config.h"
#include "server/rank_worker.h"

namespace {

constexpr const char* kUsage =
    "Usage: holotraced --config FILE\n"
    "  The light-field rendering daemon (docs/SERVICE.md). SIGTERM/SIGINT: graceful stop; SIGHUP: reload displays.\n";

sigset_t handledSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGHUP);
  return set;
}

int serve(ht::server::DaemonConfig config, std::unique_ptr<ht::server::DistributedFrames> cluster = nullptr) {
  const sigset_t signals = handledSignals();
  ht::server::Daemon daemon(std::move(config), std::cerr, std::move(cluster));
  daemon.start();
  std::cerr << "holotraced: ready" << std::endl;
  for (;;) {
    int sig = 0;
    if (sigwait(&signals, &sig) != 0) continue;
    if (sig == SIGHUP) {
      std::cerr << "holotraced: SIGHUP, " << daemon.reloadDisplays() << " displays" << std::endl;
      continue;
    }
    std::cerr << "holotraced: " << strsignal(sig) << ", shutting down" << std::endl;
    daemon.shutdown();
    std::cerr << "holotraced: stopped" << std::endl;
    return 0;
  }
}

// Every rank of `mpirun -np N holotraced --config C`. Rank 0 serves; the others render until rank 0 stops them.
int serveUnderMpirun(const std::string& configPath) {
  namespace server = ht::server;
  const std::unique_ptr<ht::cluster::Communicator> comm =
      ht::cluster::Communicator::join(ht::cluster::ThreadUse::Serialized);
  const std::string prefix =
      "holotraced: rank " + std::to_string(comm->rank()) + " of " + std::to_string(comm->size()) + ": ";
  try {
    server::DaemonConfig config = server::loadDaemonConfig(configPath);
    std::vector<server::RankInfo> ranks = server::startCluster(*comm, config);
    if (comm->rank() != 0) {
      std::cerr << prefix << "rendering for rank 0 (pid " << ::getpid() << ")" << std::endl;
      server::runWorkerRank(*comm, config, std::cerr);
      std::cerr << prefix << "stopped by rank 0" << std::endl;
      return 0;
    }
    if (comm->size() == 1) return serve(std::move(config));
    return serve(std::move(config), std::make_unique<server::ClusterFrames>(*comm, std::move(ranks), std::cerr));
  } catch (const ht::cluster::RankMismatchError& e) {
    std::cerr << prefix << "error: " << e.what() << std::endl;
    return 2;  // every rank got the same verdict at the start-up check: all end cleanly
  } catch (const std::exception& e) {
    std::cerr << prefix << "error: " << e.what() << std::endl;
    comm->abort(1);
  }
  return 1;  // not reached: abort() ends the process
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::cout << kUsage;
    return 0;
  }
  if (argc != 3 || std::strcmp(argv[1], "--config") != 0) {
    std::cerr << kUsage;
    return 2;
  }
  const sigset_t signals = handledSignals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);  // before any thread starts (MPI's too): all inherit the mask
  ::signal(SIGXFSZ, SIG_IGN);  // over RLIMIT_FSIZE a write fails with EFBIG (-> RESOURCE_EXHAUSTED), no crash
  try {
    if (ht::cluster::launcherWorldSize()) return serveUnderMpirun(argv[2]);
    return serve(ht::server::loadDaemonConfig(argv[2]));
  } catch (const std::exception& e) {
    std::cerr << "holotraced: " << e.what() << "\n";
    return 1;
  }
}
