// slab_test.h - conservative ray / box slab test for the two child boxes of a GpuBvhNode (C++ and GLSL).
//
// Robustness measures (docs/BVH.md §5.2):
//  * safe reciprocal: |d| below 1e-18 is replaced by +-1e-18 keeping the sign (also of -0), so 1/d is finite
//    and (plane - o) * (1/d) never evaluates 0 * inf = NaN when the origin lies on a slab plane.
//    Semantics of Embree's zero_fix (common/math/vec3fa.h, min_rcp_input = 1e-18); tinybvh safercp is the
//    same idea with a 1e-12 threshold. Avoids the pitfall of tinybvh's GLSL safe_rcp (sign(0) = 0 -> inf).
//  * Ize, "Robust BVH Ray Traversal", JCGT 2(2) 2013, as in pbrt-v3 Bounds3::IntersectP: each slab distance
//    t = (plane - o) * (1/d) carries at most 3 roundings (subtraction, reciprocal, product), so scaling the
//    exit distance by 1 + 2*gamma(3) makes the test conservative: a ray that truly meets the box is never
//    culled. The form (plane - o) * rcp is required for that bound (plane*rcp - o*rcp can cancel).
//  * near / far planes are selected by the sign of the direction (Williams et al. 2005; pbrt dirIsNeg), not by
//    min/max of the two plane distances, so an empty box (lo = +inf, hi = -inf) always yields
//    tNear = +inf > tFar = -inf and is never entered.
//  * NaN-ordered min/max (madmann91/bvh src/bvh/v2/utils.h robust_min/robust_max): a NaN slab distance in the
//    first operand drops out; the ray's own tmin/tmax (never NaN after validation) go last.
#ifndef HT_SLAB_TEST_H
#define HT_SLAB_TEST_H
#include "common/glsl_cpp.h"
#include "bvh/float_bounds.h"
#include "bvh/gpu_node.h"
#include "common/exact_division.h"

HT_SHARED_BEGIN

HT_CONST float HT_MIN_RCP_INPUT = 1e-18f;

// NaN-ordered minimum: returns b when a is NaN (a < b is false).
HT_INLINE float ht_min_nan(float a, float b) { return a < b ? a : b; }
// NaN-ordered maximum: returns b when a is NaN.
HT_INLINE float ht_max_nan(float a, float b) { return a > b ? a : b; }

// 1/x with |x| clamped to >= HT_MIN_RCP_INPUT, sign (including that of -0) preserved: finite for finite x.
HT_INLINE float ht_safe_rcp(float x) {
  uint signBit = floatBitsToUint(x) & 0x80000000u;
  float clamped = abs(x) < HT_MIN_RCP_INPUT ? uintBitsToFloat(signBit | floatBitsToUint(HT_MIN_RCP_INPUT)) : x;
  return ht_div(1.0f, clamped);
}

// Per-ray data of the slab test, computed once per ray.
struct HtSlabRay {
  vec3 origin;
  vec3 invDir;  // ht_safe_rcp of each direction component
  bool negX;    // direction component < 0 (the near plane is the box's hi plane)
  bool negY;
  bool negZ;
  float tmin;
};

HT_INLINE HtSlabRay ht_make_slab_ray(vec3 origin, vec3 dir, float tmin) {
  HtSlabRay r;
  r.origin = origin;
  r.invDir = vec3(ht_safe_rcp(dir.x), ht_safe_rcp(dir.y), ht_safe_rcp(dir.z));
  // sign of the clamped reciprocal: -0 gives -1e18, so use the sign bit rather than dir < 0
  r.negX = r.invDir.x < 0.0f;
  r.negY = r.invDir.y < 0.0f;
  r.negZ = r.invDir.z < 0.0f;
  r.tmin = tmin;
  return r;
}

// Conservative test of one box given as (lo.x, hi.x, lo.y, hi.y) and (lo.z, hi.z).
// Returns whether [tmin, tmax] meets the box; tEnter = entry distance (>= tmin) for ordering.
HT_INLINE bool ht_slab_box(HT_IN(HtSlabRay) r, vec4 xy, float loZ, float hiZ, float tmax, HT_OUT(float) tEnter) {
  HT_PRECISE float tx0 = ((r.negX ? xy.y : xy.x) - r.origin.x) * r.invDir.x;
  HT_PRECISE float tx1 = ((r.negX ? xy.x : xy.y) - r.origin.x) * r.invDir.x;
  HT_PRECISE float ty0 = ((r.negY ? xy.w : xy.z) - r.origin.y) * r.invDir.y;
  HT_PRECISE float ty1 = ((r.negY ? xy.z : xy.w) - r.origin.y) * r.invDir.y;
  HT_PRECISE float tz0 = ((r.negZ ? hiZ : loZ) - r.origin.z) * r.invDir.z;
  HT_PRECISE float tz1 = ((r.negZ ? loZ : hiZ) - r.origin.z) * r.invDir.z;
  float tNear = ht_max_nan(tx0, ht_max_nan(ty0, ht_max_nan(tz0, r.tmin)));
  HT_PRECISE float tFar = ht_min_nan(tx1, ht_min_nan(ty1, tz1)) * HT_SLAB_FAR_SCALE;
  tFar = ht_min_nan(tFar, tmax);
  tEnter = tNear;
  return tNear <= tFar;
}

// Tests BOTH child boxes of a node, given as its c0xy, c1xy, c01z members, against [r.tmin, tmax];
// returns the entry distances.
HT_INLINE void ht_slab_boxes(HT_IN(HtSlabRay) r, vec4 c0xy, vec4 c1xy, vec4 c01z, float tmax, HT_OUT(bool) hit0,
                             HT_OUT(bool) hit1, HT_OUT(float) tEnter0, HT_OUT(float) tEnter1) {
  hit0 = ht_slab_box(r, c0xy, c01z.x, c01z.y, tmax, tEnter0);
  hit1 = ht_slab_box(r, c1xy, c01z.z, c01z.w, tmax, tEnter1);
}

// Tests BOTH child boxes of a node against the ray segment [r.tmin, tmax]; returns the entry distances.
HT_INLINE void ht_slab_node(HT_IN(HtSlabRay) r, HT_IN(GpuBvhNode) n, float tmax, HT_OUT(bool) hit0, HT_OUT(bool) hit1,
                            HT_OUT(float) tEnter0, HT_OUT(float) tEnter1) {
  ht_slab_boxes(r, n.c0xy, n.c1xy, n.c01z, tmax, hit0, hit1, tEnter0, tEnter1);
}

HT_SHARED_END
#endif
