// exact_division.h - a / b and sqrt(x) rounded to nearest as IEEE 754 rounds C++'s, in GLSL as in C++.
//
// Vulkan lets a driver divide with an error of up to 2.5 ULP (Vulkan spec, "Precision and Operation of SPIR-V
// Instructions": OpFDiv), and NVIDIA's driver does so (a reciprocal and a multiply); lavapipe divides exactly.
// A quotient that the CPU reference and the shader must share bit for bit (the ray's shear constants, 1/det of a
// hit, a slab test's reciprocal, an accumulated mean) is therefore computed in double and rounded once to float:
// the double quotient is within 2.5 double ULP (at most 2^-50.7 relative) of a / b, while a quotient of two floats
// that is not itself a float lies at least 2^-49 (relative) from the midpoint of two floats, so the rounding to float
// is the same as that of the exact quotient (the argument of Figueroa, "When is double rounding innocuous?", SIGNUM
// 1995, with the driver's error added). Costs a double division; used once per ray, per hit or per target, never
// per node. Seen on an H200: docs/DRIVERS.md.
#ifndef HT_EXACT_DIVISION_H
#define HT_EXACT_DIVISION_H
#include "common/glsl_cpp.h"
#ifndef HT_GLSL
#include <cmath>
#endif

HT_SHARED_BEGIN

#ifdef HT_GLSL
HT_INLINE float ht_div(float a, float b) { return float(double(a) / double(b)); }
HT_INLINE vec3 ht_div3(vec3 a, float b) { return vec3(dvec3(a) / double(b)); }
// sqrt: Vulkan's is 1/inversesqrt, up to about 4.5 double ULP (2^-49.8 relative), and the root of a float can lie
// as close as 2^-50 to a float midpoint, so the double root rounded to float may be one float off. It is then
// corrected exactly: a midpoint between two floats has at most 25 significant bits, so its square is exact in
// double, and comparing it with x says on which side of the midpoint the true root lies.
HT_INLINE float ht_sqrt(float x) {
  float s = float(sqrt(double(x)));
  if (!(x > 0.0f) || isinf(x)) return s;  // 0, negative or NaN, +inf: nothing to correct
  double up = 0.5 * (double(s) + double(uintBitsToFloat(floatBitsToUint(s) + 1u)));
  double down = 0.5 * (double(s) + double(uintBitsToFloat(floatBitsToUint(s) - 1u)));
  if (up * up < double(x)) return uintBitsToFloat(floatBitsToUint(s) + 1u);
  if (down * down > double(x)) return uintBitsToFloat(floatBitsToUint(s) - 1u);
  return s;
}
#else
HT_INLINE float ht_div(float a, float b) { return a / b; }
HT_INLINE vec3 ht_div3(vec3 a, float b) { return a / b; }
HT_INLINE float ht_sqrt(float x) { return std::sqrt(x); }
#endif

HT_SHARED_END

#endif  // HT_EXACT_DIVISION_H
