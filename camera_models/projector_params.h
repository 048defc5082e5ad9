// projector_params.h - GPU-visible parameter block of the HPO projector-array model (projector_model.h). std430-safe:
// only vec4/ivec4/mat4 members.
#ifndef HT_PROJECTOR_PARAMS_H
#define HT_PROJECTOR_PARAMS_H
#include "common/glsl_cpp.h"
#include "camera_models/camera_params.h"  // LensDistortion

HT_SHARED_BEGIN

HT_CONST uint HT_MAX_PROJECTORS = 128u;

// HoloVizio-class array of N projectors on a planar diffusing screen (docs/OPTICS.md §6, §9 M3).
struct ProjectorArrayParams {
  vec4 observer;      // x observer distance Dobs (> 0), y observer height h, z angular scattering (rad), w count N
  vec4 scale;         // x world units per display unit, yzw unused
  mat4 localToWorld;  // display-local frame (screen centre, x right, y up, +z toward the viewer) -> world, unscaled
  // The projectors' lens (all alike): x focal length f (px), y unused, zw principal point offset from the image
  // centre (px); distortion as in lens_distortion.h (radial.w = 0: an ideal lens, the rest unused).
  vec4 lens;
  LensDistortion distortion;
  // Projector k: columns 0-2, rows 0-2 = the 3x3 pixel -> screen homography H (column-major as GLSL mat3:
  // projector[k][c][r] = H[r][c]); projector[k][0].w, [1].w = image width, height (px); column 3 = position (xyz, 1).
  mat4 projector[HT_MAX_PROJECTORS];
};

HT_SHARED_END
#endif  // HT_PROJECTOR_PARAMS_H
