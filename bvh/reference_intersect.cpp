// reference_intersect.cpp - see reference_intersect.h. Woop, Benthin, Wald, JCGT 2(1) 2013 (docs/BVH.md §5.1),
// all in double precision, no error bound other than t > 0.
#include "bvh/reference_intersect.h"

#include <cmath>

namespace ht::bvh {

ReferenceHit referenceIntersectTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                                        const gpu_shared::HtRay& ray) {
  ReferenceHit miss;
  miss.t = ray.tmax;
  const glm::dvec3 o(ray.origin);
  const glm::dvec3 d(ray.dir);
  const glm::dvec3 ad = glm::abs(d);
  const int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  const int kx = (kz + 1) % 3;
  const int ky = (kx + 1) % 3;
  if (d[kz] == 0.0) return miss;
  const double sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1.0 / d[kz];
  auto shear = [&](const glm::dvec3& p) {
    glm::dvec3 q = p - o;
    return glm::dvec3(q[kx] - sx * q[kz], q[ky] - sy * q[kz], sz * q[kz]);
  };
  const glm::dvec3 A = shear(a), B = shear(b), C = shear(c);
  const double U = C.x * B.y - C.y * B.x;
  const double V = A.x * C.y - A.y * C.x;
  const double W = B.x * A.y - B.y * A.x;
  if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return miss;
  const double det = U + V + W;
  if (det == 0.0) return miss;
  const double t = (U * A.z + V * B.z + W * C.z) / det;
  if (!(t > 0.0) || t < ray.tmin || t > ray.tmax) return miss;
  ReferenceHit hit;
  hit.hit = true;
  hit.t = t;
  hit.u = V / det;
  hit.v = W / det;
  return hit;
}

ReferenceHit referenceClosestHit(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                 const gpu_shared::HtRay& ray) {
  ReferenceHit best;
  best.t = ray.tmax;
  for (uint32_t id = 0; id < triangles.size(); ++id) {
    const glm::uvec3& tri = triangles[id];
    if (tri.x >= positions.size() || tri.y >= positions.size() || tri.z >= positions.size()) continue;
    ReferenceHit h = referenceIntersectTriangle(glm::dvec3(positions[tri.x]), glm::dvec3(positions[tri.y]),
                                                glm::dvec3(positions[tri.z]), ray);
    if (h.hit && (!best.hit || h.t < best.t)) {
      best = h;
      best.triId = id;
    }
  }
  return best;
}

}  // namespace ht::bvh
