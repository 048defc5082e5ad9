#include "hit_agreement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace ht::accuracy {
namespace {

using gpu_shared::HT_MISS;

struct Geometry {
  double minBarycentric;
  double cosine;
};

Geometry hitGeometry(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                     const gpu_shared::HtRay& ray, const gpu_shared::HtHit& hit) {
  const double u = hit.u, v = hit.v;
  const glm::uvec3 idx = triangles[hit.triId];
  const glm::dvec3 a(positions[idx.x]), b(positions[idx.y]), c(positions[idx.z]);
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const glm::dvec3 d(ray.dir);
  const double len = glm::length(n) * glm::length(d);
  return {std::min({u, v, 1.0 - u - v}), len > 0.0 ? std::abs(glm::dot(n, d)) / len : 0.0};
}

Cause classify(const Geometry& g) {
  if (g.minBarycentric < 1e-4) return Cause::EdgeOrVertex;
  if (g.cosine < 1e-3) return Cause::Graze;
  return Cause::Interior;
}

double maxAbsCoordinate(std::span<const glm::vec3> positions) {
  double m = 0.0;
  for (const glm::vec3& p : positions)
    m = std::max({m, double(std::abs(p.x)), double(std::abs(p.y)), double(std::abs(p.z))});
  return m;
}

double tTolerance(const gpu_shared::HtRay& ray, double t, double sceneMagnitude) {
  const glm::dvec3 o(ray.origin), d(ray.dir);
  const double originMagnitude = std::max({std::abs(o.x), std::abs(o.y), std::abs(o.z)});
  return 64.0 * std::numeric_limits<float>::epsilon() * (t + (originMagnitude + sceneMagnitude) / glm::length(d));
}

}  // namespace

std::string causeName(Cause cause) {
  static const char* const kNames[] = {"edge-or-vertex", "silhouette-graze", "interior"};
  return kNames[static_cast<uint32_t>(cause)];
}

double Agreement::agreementPercent() const {
  return rays == 0 ? 100.0 : 100.0 * (1.0 - double(hitMissDisagreements) / double(rays));
}

Agreement compareHits(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                      std::span<const gpu_shared::HtRay> rays, std::span<const gpu_shared::HtHit> ours,
                      std::span<const gpu_shared::HtHit> anchor, size_t maxListed) {
  Agreement a;
  a.rays = rays.size();
  const double sceneMagnitude = maxAbsCoordinate(positions);
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool oursHit = ours[i].triId != HT_MISS, anchorHit = anchor[i].triId != HT_MISS;
    if (!oursHit && !anchorHit) continue;
    Disagreement d{i, ours[i], anchor[i], oursHit != anchorHit};
    if (!d.hitMiss && std::abs(double(ours[i].t) - anchor[i].t) <= tTolerance(rays[i], anchor[i].t, sceneMagnitude)) {
      continue;
    }
    (d.hitMiss ? a.hitMissDisagreements : a.tDisagreements)++;
    const Geometry g = hitGeometry(positions, triangles, rays[i], anchorHit ? anchor[i] : ours[i]);
    // Where both hit different triangles, either one lying at an edge explains the difference.
    const Geometry other = oursHit && anchorHit ? hitGeometry(positions, triangles, rays[i], ours[i]) : g;
    d.minBarycentric = std::min(g.minBarycentric, other.minBarycentric);
    d.cosine = std::min(g.cosine, other.cosine);
    d.cause = classify(Geometry{d.minBarycentric, d.cosine});
    a.byCause[static_cast<uint32_t>(d.cause)]++;
    if (a.listed.size() < maxListed) a.listed.push_back(d);
  }
  return a;
}

std::string describe(const Disagreement& d) {
  std::ostringstream s;
  s.precision(9);
  s << "ray " << d.ray << (d.hitMiss ? " hit/miss" : " t") << " [" << causeName(d.cause) << "] ours tri "
    << static_cast<int64_t>(d.ours.triId == HT_MISS ? -1 : int64_t(d.ours.triId)) << " t " << d.ours.t
    << ", embree tri " << (d.anchor.triId == HT_MISS ? -1 : int64_t(d.anchor.triId)) << " t " << d.anchor.t
    << ", min barycentric " << d.minBarycentric << ", |cos| " << d.cosine;
  return s.str();
}

}  // namespace ht::accuracy
