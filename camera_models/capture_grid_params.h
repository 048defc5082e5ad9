// capture_grid_params.h - GPU-visible parameter block of the two-plane capture grid (capture_grid_model.h).
// std430-safe: only vec4/ivec4/mat4 members.
#ifndef HT_CAPTURE_GRID_PARAMS_H
#define HT_CAPTURE_GRID_PARAMS_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

// Regular (s, t) camera grid with sheared frusta through a shared (u, v) window (docs/OPTICS.md §9 M5).
struct CaptureGridParams {
  ivec4 grid;         // x columns, y rows, z image width (px), w image height (px)
  vec4 geometry;      // x spacing ds, y spacing dt, z distance (camera plane z), w unused
  vec4 window;        // x window width, y window height, zw unused
  mat4 localToWorld;  // display-local frame (window centre, +z toward the cameras) -> world
};

HT_SHARED_END
#endif  // HT_CAPTURE_GRID_PARAMS_H
