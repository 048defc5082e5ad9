// float_bounds.h - floating-point error constants shared by the slab test and the watertight triangle test
// (C++ and GLSL). Written as decimal literals of the exact float values so that glslang's constant folding
// and the C++ compiler produce bit-identical constants.
//
// Source: pbrt-v3 src/core/pbrt.h (MachineEpsilon = FLT_EPSILON * 0.5,
//   gamma(n) = n*eps / (1 - n*eps), evaluated in float), pbr-book 3rd ed. §3.9 "Managing Rounding Error";
//   docs/BVH.md §5.1, §5.2.
#ifndef HT_FLOAT_BOUNDS_H
#define HT_FLOAT_BOUNDS_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

// Unit roundoff of IEEE binary32, 2^-24.
HT_CONST float HT_MACHINE_EPSILON = 5.9604644775390625e-8f;
// gamma(n) = n*eps/(1-n*eps) rounded to float (bits 0x34000001, 0x34400002, 0x34a00003).
HT_CONST float HT_GAMMA2 = 1.1920930376163597e-7f;
HT_CONST float HT_GAMMA3 = 1.7881396274788131e-7f;
HT_CONST float HT_GAMMA5 = 2.9802330914208142e-7f;
// Ize's conservative far-plane factor 1 + 2*gamma(3) = 1 + 3 ulp(1) (bits 0x3f800003); equals Embree's
// rdir_far = (1 + 3 ulp) * rdir (kernels/bvh/node_intersector1.h), docs/BVH.md §5.2.
HT_CONST float HT_SLAB_FAR_SCALE = 1.00000035762786865234375f;
// Largest finite float: |x| <= HT_FLOAT_MAX is false for NaN and +-Inf.
HT_CONST float HT_FLOAT_MAX = 3.40282346638528859811704183484516925e38f;

HT_SHARED_END
#endif
