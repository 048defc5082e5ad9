// rank_identity.cpp - see rank_identity.h.
#include "cluster/rank_identity.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <type_traits>
#include <variant>

#include "cluster/cluster_error.h"
#include "cluster/content_hash.h"

#ifndef HT_BUILD_ID
#error "HT_BUILD_ID must be defined by cluster/CMakeLists.txt"
#endif

namespace ht::cluster {
namespace {

constexpr std::size_t kFieldBytes = 256;
constexpr std::size_t kFields = 4;

std::array<std::string RankIdentity::*, kFields> fields() {
  return {&RankIdentity::build, &RankIdentity::display, &RankIdentity::scene, &RankIdentity::settings};
}
constexpr std::array<const char*, kFields> kFieldNames = {"build", "display config", "scene", "render settings"};

std::vector<std::uint8_t> pack(const RankIdentity& identity) {
  std::vector<std::uint8_t> bytes(kFields * kFieldBytes, 0);
  for (std::size_t f = 0; f < kFields; ++f) {
    const std::string& value = identity.*fields()[f];
    std::memcpy(bytes.data() + f * kFieldBytes, value.data(), std::min(value.size(), kFieldBytes - 1));
  }
  return bytes;
}

RankIdentity unpack(const std::uint8_t* bytes) {
  RankIdentity identity;
  for (std::size_t f = 0; f < kFields; ++f) {
    const char* text = reinterpret_cast<const char*>(bytes + f * kFieldBytes);
    identity.*fields()[f] = std::string(text, strnlen(text, kFieldBytes));
  }
  return identity;
}

std::string shortDigest(const std::string& value) { return value.size() > 16 ? value.substr(0, 16) + "…" : value; }

}  // namespace

std::string buildId() { return "holotrace " HT_BUILD_ID; }

std::string displayDigest(const std::string& displayName, const gpu::DisplayCamera& camera) {
  ContentHash hash;
  hash.add(displayName).addValue(camera.camera.index());
  std::visit(
      [&hash](const auto& params) {
        using T = std::decay_t<decltype(params)>;
        if constexpr (std::is_same_v<T, gpu::RayTableCamera>) {
          hash.addValue(params.params);
          if (params.table) {
            hash.addValue(params.table->width).addValue(params.table->height);
            hash.add(std::span(reinterpret_cast<const std::uint8_t*>(params.table->origins.data()),
                               params.table->origins.size() * sizeof(glm::vec3)));
            hash.add(std::span(reinterpret_cast<const std::uint8_t*>(params.table->directions.data()),
                               params.table->directions.size() * sizeof(glm::vec3)));
          }
        } else {
          hash.addValue(params);  // std430 blocks of vec4 / ivec4 / mat4 members: no padding bytes
        }
      },
      camera.camera);
  hash.addValue(camera.shape);
  if (camera.quilt) {
    const QuiltLayout& q = *camera.quilt;
    hash.addValue(q.columns).addValue(q.rows).addValue(q.quiltWidth).addValue(q.quiltHeight).addValue(q.aspect);
  }
  return hash.hex();
}

std::string settingsDigest(const gpu::RenderSettings& s) {
  ContentHash hash;
  hash.addValue(s.spp).addValue(s.filter).addValue(s.maxDepth).addValue(s.seed).addValue(s.refineSpp);
  hash.addValue(s.refineContrast).addValue(static_cast<std::uint8_t>(s.forceAllFeatures));
  return hash.hex();
}

std::vector<std::string> identityMismatches(const std::vector<RankIdentity>& ranks) {
  std::vector<std::string> lines;
  for (std::size_t r = 1; r < ranks.size(); ++r) {
    for (std::size_t f = 0; f < kFields; ++f) {
      const std::string& mine = ranks[r].*fields()[f];
      const std::string& root = ranks[0].*fields()[f];
      if (mine == root) continue;
      lines.push_back("rank " + std::to_string(r) + " has another " + kFieldNames[f] + " than rank 0 (" +
                      shortDigest(mine) + " vs " + shortDigest(root) + ")");
      break;
    }
  }
  return lines;
}

void checkRankIdentities(Communicator& comm, const RankIdentity& mine) {
  const std::vector<std::uint8_t> all = comm.allGather(pack(mine));
  std::vector<RankIdentity> ranks;
  for (int r = 0; r < comm.size(); ++r)
    ranks.push_back(unpack(all.data() + static_cast<std::size_t>(r) * kFields * kFieldBytes));
  const std::vector<std::string> mismatches = identityMismatches(ranks);
  if (mismatches.empty()) return;
  std::string message = "the " + std::to_string(comm.size()) + " ranks of this job do not render the same frame: ";
  for (std::size_t i = 0; i < mismatches.size(); ++i) message += (i ? "; " : "") + mismatches[i];
  message += ". Start every rank with the same holotrace build, --display config, --scene and render options.";
  throw RankMismatchError(message);
}

}  // namespace ht::cluster
