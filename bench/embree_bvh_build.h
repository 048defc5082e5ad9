// embree_bvh_build.h - Embree 3's BVH builder (rtcBuildBVH) building a binary tree in our own memory, converted to
// a bvh::Bvh2 so that the same SAH-cost formula (bvh::sahCost) and the same CPU traversal counter apply to both
// builders. Settings mirror ours (bvh_builder.h): binary, leaves of 1..4 triangles, C_trav = C_int = 1,
// RTC_BUILD_QUALITY_MEDIUM (Embree's binned SAH; HIGH would need spatial splits, which duplicate triangles).
#pragma once
#include <span>

#include <glm/glm.hpp>

#include "bvh/bvh_builder.h"

namespace ht::bench {

struct EmbreeBvhBuild {
  bvh::Bvh2 tree;        // tree.report.sahCost / nodeCount / leafCount / maxDepth filled like ours
  double buildMs = 0;    // wall time of rtcBuildBVH alone (callbacks allocate the nodes)
  double convertMs = 0;  // flattening into Bvh2 (not part of the build time)
};

// Throws ht::Error on an Embree error. Triangles with a zero-area or non-finite box are passed on as they are.
EmbreeBvhBuild buildEmbreeBvh(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                              std::uint32_t maxLeafSize);

}  // namespace ht::bench
