// quilt_params.h - GPU-visible parameter block of the quilt view-array model (quilt_model.h). std430-safe: only
// vec4/ivec4/mat4 members, so C++ (GLM) and GLSL agree on the layout without padding rules.
#ifndef HT_QUILT_PARAMS_H
#define HT_QUILT_PARAMS_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

// Sheared (off-axis) view array of a Looking Glass quilt (docs/OPTICS.md §4.3, §9 M1).
struct QuiltParams {
  vec4 camera;        // x focal distance D, y focal-rectangle height (targetDiam), z render aspect W/H,
                      // w viewCone (rad, full cone)
  ivec4 tiles;        // x columns, y rows, z tile width (px), w tile height (px)
  vec4 views;         // x view count N (float), yzw unused
  mat4 localToWorld;  // display-local frame (x right, y up, +z toward the viewer, origin = focal-plane centre) -> world
};

HT_SHARED_END
#endif  // HT_QUILT_PARAMS_H
