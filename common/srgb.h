// srgb.h - the sRGB transfer functions (IEC 61966-2-1:1999, section 5), one source for C++ and GLSL: image output
// (frame_io/srgb8.h), the adaptive-refinement contrast kernel (gpu/adaptive_refinement.h) and the image-quality
// metrics of the benchmarks (bench/image_metrics.h) all encode through ht_srgb_encode.
//
//   encode (OETF):  V = 12.92 L                 for L <= 0.0031308
//                   V = 1.055 L^(1/2.4) - 0.055 otherwise
//   decode (EOTF):  L = V / 12.92               for V <= 0.04045
//                   L = ((V + 0.055) / 1.055)^2.4 otherwise
//
// Both clamp their input to [0, 1] first, so out-of-range and infinite values saturate; NaN maps to 0 (the comparison
// `x > 0` is false for NaN in C++ and GLSL alike, where clamp() of NaN is undefined). For x in [0, 1] the encoded value
// stays <= 1: 1.055f - 0.055f rounds to 0.99999994 in float. The arithmetic is the same float arithmetic in both
// languages (f-suffixed literals, C++ built with -ffp-contract=off).
#ifndef HT_COMMON_SRGB_H
#define HT_COMMON_SRGB_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

// `value` clamped to [0, 1]; NaN -> 0.
HT_INLINE float ht_clamp_unit(float value) { return value > 0.0f ? min(value, 1.0f) : 0.0f; }

// Linear value -> sRGB-encoded value in [0, 1].
HT_INLINE float ht_srgb_encode(float linear) {
  float x = ht_clamp_unit(linear);
  return x <= 0.0031308f ? 12.92f * x : 1.055f * pow(x, 1.0f / 2.4f) - 0.055f;
}

// sRGB-encoded value -> linear value in [0, 1] (the inverse of ht_srgb_encode up to float rounding).
HT_INLINE float ht_srgb_decode(float encoded) {
  float v = ht_clamp_unit(encoded);
  return v <= 0.04045f ? v / 12.92f : pow((v + 0.055f) / 1.055f, 2.4f);
}

HT_SHARED_END
#endif
