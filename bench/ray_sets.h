// ray_sets.h - the ray sets of holotrace-bench-traversal, all derived from one pinhole primary batch:
//   primary  closest hit, pinhole rays through pixel centres, reordered into 16x16 tiles (consecutive = coherent)
//   shadow   any hit, from each primary hit point (ht_offset_ray) to a point light above-front of the bounds
//   diffuse  closest hit, cosine-weighted bounce about the geometric normal (incoherent)
//   mirror   closest hit, mirror reflection of the primary direction (semi-coherent)
// Secondary rays exist only for primary rays that hit; they keep the primary order. Every set is traced by every
// tracer, so the figures compare tracers on identical rays.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "bvh/ray_types.h"
#include "scene/scene.h"

namespace ht::bench {

enum class RayQuery { Closest, Occluded };

struct RaySet {
  std::string name;  // "primary", "shadow", "diffuse", "mirror"
  RayQuery query = RayQuery::Closest;
  std::vector<gpu_shared::HtRay> rays;
};

// size x size pinhole rays framing the bounds (primary_ray_batch.h), in 16x16-tile order.
RaySet makeTiledPrimaryRays(const Bounds3& bounds, std::uint32_t size);

// The three secondary sets from the primary rays and their closest hits (hit.triId indexes scene.triangles).
std::vector<RaySet> makeSecondaryRays(const Scene& scene, std::span<const gpu_shared::HtRay> primary,
                                      std::span<const gpu_shared::HtHit> hits, std::uint32_t seed);

}  // namespace ht::bench
