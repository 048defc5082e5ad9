// cluster_start.cpp - see cluster_start.h.
#include "server/cluster_start.h"

#include <unistd.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "cluster/cluster_error.h"
#include "cluster/content_hash.h"
#include "cluster/rank_identity.h"
#include "server/display_registry.h"

namespace ht::server {
namespace {

constexpr std::size_t kHostBytes = 64;

// Every display the rank would serve: id, config text and ray table (the same bytes trace the same rays).
std::string displaysDigest(const DaemonConfig& config) {
  DisplayRegistry displays(config.displaysDir, deviceScanFor(config.devices));
  std::ostream silent(nullptr);
  displays.reload(silent);
  cluster::ContentHash hash;
  for (const auto& display : displays.list()) {
    hash.add(display->id).add(display->sourceText);
    if (const auto& table = display->rayTable) {
      hash.addValue(table->width).addValue(table->height);
      hash.add(std::span(reinterpret_cast<const std::uint8_t*>(table->origins.data()),
                         table->origins.size() * sizeof(table->origins[0])));
      hash.add(std::span(reinterpret_cast<const std::uint8_t*>(table->directions.data()),
                         table->directions.size() * sizeof(table->directions[0])));
    }
  }
  return hash.hex();
}

std::string configFileDigest(const DaemonConfig& config) {
  std::ifstream in(config.sourcePath, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return cluster::ContentHash().add(text).hex();
}

std::vector<RankInfo> exchangeRankInfo(cluster::Communicator& comm) {
  std::vector<std::uint8_t> mine(kHostBytes + sizeof(std::uint32_t), 0);
  char host[kHostBytes] = {};
  ::gethostname(host, kHostBytes - 1);
  std::memcpy(mine.data(), host, kHostBytes);
  const auto pid = static_cast<std::uint32_t>(::getpid());
  std::memcpy(mine.data() + kHostBytes, &pid, sizeof pid);
  const std::vector<std::uint8_t> all = comm.allGather(mine);
  std::vector<RankInfo> ranks(static_cast<std::size_t>(comm.size()));
  for (std::size_t r = 0; r < ranks.size(); ++r) {
    const std::uint8_t* at = all.data() + r * mine.size();
    ranks[r].host =
        std::string(reinterpret_cast<const char*>(at), strnlen(reinterpret_cast<const char*>(at), kHostBytes));
    std::memcpy(&ranks[r].pid, at + kHostBytes, sizeof(std::uint32_t));
  }
  return ranks;
}

}  // namespace

std::vector<RankInfo> startCluster(cluster::Communicator& comm, const DaemonConfig& config) {
  // The identity's "display config" is every display of the registry, its "render settings" the daemon's config
  // file; scenes are rank 0's to send, so they are not compared here.
  try {
    cluster::checkRankIdentities(comm, {cluster::buildId(), displaysDigest(config), "", configFileDigest(config)});
  } catch (const cluster::RankMismatchError& e) {
    throw cluster::RankMismatchError(std::string(e.what()) +
                                     " (holotraced compares its build, every display it serves and its --config "
                                     "file, shown as 'render settings')");
  }
  return exchangeRankInfo(comm);
}

}  // namespace ht::server
