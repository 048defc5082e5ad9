// oblique_params.h - GPU-visible parameter block of the oblique (sheared orthographic) direction camera
// (oblique_model.h, docs/OPTICS.md §9 M6). std430-safe: only vec4/ivec4/mat4 members.
#ifndef HT_OBLIQUE_PARAMS_H
#define HT_OBLIQUE_PARAMS_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

// One parallel-ray image per direction e_k of a columns x rows direction grid (view = j*columns + i, bottom-left
// first). Display-local frame: window centred on the origin in the plane z = 0, +z toward the viewer.
struct ObliqueParams {
  ivec4 grid;         // x columns, y rows, z image width (px), w image height (px)
  vec4 cone;          // x horizontal cone (full, radians), y vertical cone (full, radians), z zFront (world), w unused
  vec4 window;        // x window width, y window height (world units), zw unused
  mat4 localToWorld;  // display-local frame (window centre) -> world
};

HT_SHARED_END
#endif  // HT_OBLIQUE_PARAMS_H
