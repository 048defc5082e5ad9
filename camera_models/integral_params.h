// integral_params.h - GPU-visible parameter block of the integral-imaging (microlens) model (integral_model.h).
// std430-safe: only vec4/ivec4/mat4 members.
#ifndef HT_INTEGRAL_PARAMS_H
#define HT_INTEGRAL_PARAMS_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

// Integral-imaging panel (docs/OPTICS.md §7, §9 M4); lengths in display units.
struct IntegralParams {
  vec4 panel;  // x LCD width (px), y LCD height (px), z pixel pitch, w sampling (0 lens centre, 1 aperture)
  vec4 lens;   // x lens pitch, y focal length f, z gap g, w front plane z (rays start there)
  vec4 grid;   // xy lens-grid offset (a lens centre), z cos(rotation), w sin(rotation)
  vec4 scale;  // x world units per display unit, yzw unused
  // Lens-grid coordinates g = R^-1 (p - offset)/pitch as g = x*A + y*B + g0, split for exact fract (integral_model.h):
  vec4 rateX;         // x, y: hi, lo of A.x (d gx / dx);  z, w: hi, lo of A.y (d gy / dx)
  vec4 rateY;         // x, y: hi, lo of B.x (d gx / dy);  z, w: hi, lo of B.y (d gy / dy)
  vec4 gridConst;     // xy fract(g0) (g at pixel (0, 0) corner), zw unused
  mat4 localToWorld;  // display-local frame (lens-plane centre, x right, y up, +z toward the viewer) -> world
};

HT_SHARED_END
#endif  // HT_INTEGRAL_PARAMS_H
