// process_stats.h - a process's resident memory, CPU time and thread count from /proc (proc(5): VmRSS and Threads
// in /proc/PID/status; utime + stime, fields 14 and 15 of /proc/PID/stat, in clock ticks). Status reports the
// daemon's own figures, so a load client can watch for leaks without access to the daemon's /proc entry.
#pragma once
#include <sys/types.h>

#include <cstdint>

namespace ht::server {

struct ProcessStats {
  std::uint64_t residentKiB = 0;
  double cpuSeconds = 0.0;  // user + system, all threads
  std::uint32_t threads = 0;
  std::uint32_t openFds = 0;  // entries of /proc/PID/fd (0 if unreadable: another user's process)
};

// Throws IoError if /proc/PID is unreadable (no such process, no /proc).
ProcessStats readProcessStats(pid_t pid);

}  // namespace ht::server
