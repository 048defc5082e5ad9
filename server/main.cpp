// main.cpp - holotraced --config FILE. Signals are taken synchronously with sigwait() on the main thread (blocked
// in every thread first): SIGTERM/SIGINT -> graceful shutdown, exit 0; SIGHUP -> reload display configs. SIGXFSZ is
// ignored, so a file-size limit fails one Capture instead of killing the daemon.
#include <signal.h>

#include <cstring>
#include <iostream>
#include <string>

#include "common/error.h"
#include "server/daemon.h"
#include "server/daemon_config.h"

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

int serve(const std::string& configPath) {
  const sigset_t signals = handledSignals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);  // before any thread starts: all threads inherit the mask
  ::signal(SIGXFSZ, SIG_IGN);  // over RLIMIT_FSIZE a write fails with EFBIG (-> RESOURCE_EXHAUSTED), no crash
  ht::server::Daemon daemon(ht::server::loadDaemonConfig(configPath), std::cerr);
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
  try {
    return serve(argv[2]);
  } catch (const std::exception& e) {
    std::cerr << "holotraced: " << e.what() << "\n";
    return 1;
  }
}
