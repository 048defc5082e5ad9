// load_options.h - command line of holotrace-bench-load (bench/load_client_main.cpp).
#pragma once
#include <cstdint>
#include <string>

namespace ht::bench {

struct LoadOptions {
  std::string socket;                // gRPC address of a running holotraced
  int clients = 8;                   // concurrent StreamFrames calls, one connection each
  double seconds = 0.0;              // stop after this long (0 = no time limit) ...
  std::uint64_t frames = 0;          // ... or this many frames in total (0 = none); neither: 10 s
  double fps = 30.0;                 // requested per client
  std::uint64_t reconnectEvery = 0;  // a client opens a new call after this many frames (0 = never)
  std::string display = "builtin:portrait";
  std::string scene = "builtin:plain";
  std::uint32_t spp = 1;
  int sampleMs = 500;                // daemon Status (RSS, CPU) sampling interval
  std::uint64_t baselineFrames = 0;  // render this many frames in-process first (0 = no baseline)
  std::string displaysDir;           // the daemon's displays_dir, for the in-process baseline
  std::string samplesCsv;            // write every daemon sample here (seconds,frames,rss_kib,cpu_s,threads)
};

extern const char* const kLoadUsage;

// Throws std::invalid_argument naming the bad option.
LoadOptions parseLoadOptions(int argc, char** argv);

}  // namespace ht::bench
