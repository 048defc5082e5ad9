// embree_ray.h - holotrace rays to Embree 3 rays (benchmarks and tests only: Embree is the comparator, never
// part of the renderer). Header-only so tests can include it without linking the benchmark code.
#pragma once
#include <embree3/rtcore.h>

#include "bvh/ray_types.h"

namespace ht::embree {

inline RTCRay toEmbreeRay(const gpu_shared::HtRay& r) {
  RTCRay ray{};
  ray.org_x = r.origin.x;
  ray.org_y = r.origin.y;
  ray.org_z = r.origin.z;
  ray.tnear = r.tmin;
  ray.dir_x = r.dir.x;
  ray.dir_y = r.dir.y;
  ray.dir_z = r.dir.z;
  ray.tfar = r.tmax;
  ray.mask = 0xFFFFFFFFu;
  return ray;
}

// A ray-hit record ready for rtcIntersect1: no hit yet.
inline RTCRayHit toEmbreeRayHit(const gpu_shared::HtRay& r) {
  RTCRayHit rh{};
  rh.ray = toEmbreeRay(r);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

}  // namespace ht::embree
