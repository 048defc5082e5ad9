// process_stats.cpp - see process_stats.h.
#include "server/process_stats.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/error.h"

namespace ht::server {
namespace {

std::string procFile(pid_t pid, const char* name) { return "/proc/" + std::to_string(pid) + "/" + name; }

void readStatusFile(pid_t pid, ProcessStats& stats) {
  std::ifstream in(procFile(pid, "status"));
  if (!in) throw IoError("cannot read " + procFile(pid, "status"));
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmRSS:", 0) == 0) stats.residentKiB = std::stoull(line.substr(6));
    if (line.rfind("Threads:", 0) == 0) stats.threads = static_cast<std::uint32_t>(std::stoul(line.substr(8)));
  }
}

// /proc/PID/stat: "pid (comm) state ..." - comm may hold spaces and ')', so fields are counted after the last ')'.
double readCpuSeconds(pid_t pid) {
  std::ifstream in(procFile(pid, "stat"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');
  if (close == std::string::npos) throw IoError("cannot parse " + procFile(pid, "stat"));
  std::istringstream fields(text.substr(close + 1));
  std::string field;
  unsigned long long utime = 0, stime = 0;
  for (int i = 3; i <= 15 && fields >> field; ++i) {  // field 3 = state
    if (i == 14) utime = std::stoull(field);
    if (i == 15) stime = std::stoull(field);
  }
  return static_cast<double>(utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

std::uint32_t countOpenFds(pid_t pid) {
  std::error_code ec;
  std::uint32_t n = 0;
  for (std::filesystem::directory_iterator it(procFile(pid, "fd"), ec), end; !ec && it != end; it.increment(ec)) ++n;
  return n;
}

}  // namespace

ProcessStats readProcessStats(pid_t pid) {
  ProcessStats stats;
  readStatusFile(pid, stats);
  stats.openFds = countOpenFds(pid);
  stats.cpuSeconds = readCpuSeconds(pid);
  return stats;
}

}  // namespace ht::server
