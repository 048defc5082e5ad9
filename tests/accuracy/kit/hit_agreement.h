// hit_agreement.h - differential comparison of two closest-hit result sets (holotrace vs robust Embree),
// with every disagreement classified by its geometric cause.
//
// Causes (the anchor's hit, or ours where only we hit, decides):
//   EdgeOrVertex   the hit's smallest barycentric is below 1e-4: the ray passes within float error of an edge
//                  or a vertex, where two correct watertight tests may pick either neighbour or, on an open
//                  mesh's boundary edge, hit or miss
//   Graze          |cos| between ray and triangle normal below 1e-3: silhouette graze, t is ill-conditioned
//   Interior       neither: a real disagreement. Tests require none.
// t agreement: both hit and |t_ours - t_anchor| <= 64 eps (t + (|o|_inf + max|v|_inf) / |d|); the second term
// is the error of the translated vertex coordinates both algorithms start from (Woop et al. JCGT 2013 §3,
// pbr-book 3rd ed. §3.9.6 error bounds of the sheared triangle), 64 eps a margin over their few roundings.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/ray_types.h"

namespace ht::accuracy {

enum class Cause : uint32_t { EdgeOrVertex = 0, Graze, Interior, Count };
std::string causeName(Cause cause);

struct Disagreement {
  uint64_t ray = 0;
  gpu_shared::HtHit ours{}, anchor{};
  bool hitMiss = false;  // one hit, the other missed (else: t or triangle differs)
  Cause cause = Cause::Interior;
  double minBarycentric = 0.0, cosine = 0.0;
};

struct Agreement {
  uint64_t rays = 0;
  uint64_t hitMissDisagreements = 0;  // one side hit, the other missed
  uint64_t tDisagreements = 0;        // both hit, t outside the tolerance
  uint64_t byCause[static_cast<uint32_t>(Cause::Count)] = {};
  std::vector<Disagreement> listed;  // at most `maxListed`
  double agreementPercent() const;   // 100 * (1 - hitMiss / rays)
  uint64_t interior() const { return byCause[static_cast<uint32_t>(Cause::Interior)]; }
};

Agreement compareHits(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                      std::span<const gpu_shared::HtRay> rays, std::span<const gpu_shared::HtHit> ours,
                      std::span<const gpu_shared::HtHit> anchor, size_t maxListed = 50);

// One line per listed disagreement, for failure messages and the report.
std::string describe(const Disagreement& d);

}  // namespace ht::accuracy
