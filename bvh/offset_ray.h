// offset_ray.h - self-intersection-free origins for secondary rays (C++ and GLSL, bit-identical).
//
// Source: Wächter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems
// ch. 6 (2019), reference code as reproduced in NVIDIAGameWorks/Falcor RaytracingTests.cpp (docs/BVH.md §5.3):
//   origin() = 1/32, float_scale() = 1/65536, int_scale() = 256.
// Each component of p moves int(256 * n) ULPs in the direction of n by integer arithmetic on the float bits
// (the sign of the step follows the sign of p, because the bit pattern of a negative float grows with its
// magnitude); components near zero (|p| < 1/32), where ULPs are tiny, instead move by n / 65536.
// n must be finite (normally unit length); it points to the side the new ray leaves towards (flip it for
// rays entering the surface).
// Integer steps are added as uint (wrap-around is defined in both languages; in GLSL int arithmetic wraps
// the same way), so C++ and GLSL produce the same bits.
#ifndef HT_OFFSET_RAY_H
#define HT_OFFSET_RAY_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

HT_CONST float HT_OFFSET_ORIGIN = 0.03125f;                // origin(): 1/32
HT_CONST float HT_OFFSET_FLOAT_SCALE = 1.52587890625e-5f;  // float_scale(): 1/65536
HT_CONST float HT_OFFSET_INT_SCALE = 256.0f;               // int_scale()

// One component: p moved int(256*n) ULPs towards the sign of n, or by n/65536 close to zero.
HT_INLINE float ht_offset_component(float p, float n) {
  int ofi = int(HT_OFFSET_INT_SCALE * n);
  int step = p < 0.0f ? -ofi : ofi;
  float pi = uintBitsToFloat(floatBitsToUint(p) + uint(step));
  HT_PRECISE float pf = p + HT_OFFSET_FLOAT_SCALE * n;
  return abs(p) < HT_OFFSET_ORIGIN ? pf : pi;
}

// Ray Tracing Gems ch. 6 offset_ray(p, n).
HT_INLINE vec3 ht_offset_ray(vec3 p, vec3 n) {
  return vec3(ht_offset_component(p.x, n.x), ht_offset_component(p.y, n.y), ht_offset_component(p.z, n.z));
}

HT_SHARED_END
#endif
