// soak_options.h - command line of holotrace-soak (bench/soak_main.cpp).
#pragma once
#include <cstdint>
#include <string>

namespace ht::bench {

struct SoakOptions {
  std::string daemonExe;    // spawn this holotraced with a private config (temp dir) ...
  std::string socket;       // ... or drive a running daemon at this address (captures then need --output-root)
  std::string displaysDir;  // spawned daemon's displays_dir (the soak display, bench/load_displays)
  std::string display = "lenticular-128";
  std::string outputRoot;      // --socket mode: the daemon's output root, so the soak removes its captures
  double seconds = 1800.0;     // main phase (default 30 minutes)
  double warmupSeconds = 0.0;  // 0 = max(5 s, 10 % of --seconds)
  int clients = 8;             // concurrent workers, each a new connection per action
  std::uint64_t seed = 1;
  double sampleSeconds = 2.0;   // daemon Status sampling interval
  double quiesceSeconds = 0.0;  // wait after the workers stop before the at-rest sample (0 = TTL + 1.5 s spawned, 5 s)
  std::uint64_t rssToleranceKiB = 24 * 1024;  // at-rest RSS may exceed the baseline by this (or 10 %)
  std::uint32_t threadTolerance = 4, fdTolerance = 4;
  std::string samplesCsv;       // every sample: seconds,rss_kib,threads,fds,sessions,scene_mib,cycles
  std::uint64_t cycles = 0;     // > 0: the run ends after this many load/render cycles (or --seconds, if sooner)
  bool loadRenderOnly = false;  // --mix load-render: every action is a short-lived load + render client
};

extern const char* const kSoakUsage;

// Throws std::invalid_argument naming the bad option.
SoakOptions parseSoakOptions(int argc, char** argv);

}  // namespace ht::bench
