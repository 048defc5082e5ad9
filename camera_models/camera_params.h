// camera_params.h - GPU-visible parameter blocks of the camera models (std430; only vec4/ivec4/mat4 members
// so C++ (GLM) and GLSL agree on the layout without padding rules).
#ifndef HT_CAMERA_PARAMS_H
#define HT_CAMERA_PARAMS_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

HT_CONST uint HT_MAX_SUBPIXEL_CELLS = 4u;

// Looking Glass lenticular panel, direct per-subpixel model (docs/OPTICS.md §2, §3, §9 M2).
struct LenticularParams {
  vec4 phase;   // x pitch_s (lenses across panel width), y tilt, z subp (u units, signed), w center
  vec4 panel;   // x screenW (px), y screenH (px), z invView (0/1), w flipSubp (0/1)
  vec4 camera;  // x focal distance D, y target height (focal rectangle height), z aspect W/H, w viewCone (rad, full
                // cone)
  ivec4 flags;  // x CellPatternMode (0-4), y subpixel cell count (0-4), z flipImageX (0/1), w flipImageY (0/1)
  vec4 cellOffset[12];  // cell k, channel c -> cellOffset[k*3+c].xy = (offX/screenW, offY/screenH);
                        // cellOffset[0].zw / [1].zw = per-pixel phase rates in x / y split hi + lo (exact fract,
                        // lenticular_model.h); other .zw unused
  mat4 localToWorld;    // display-local frame (x right, y up, +z toward viewer, origin = focal-plane centre) -> world
};

// Brown-Conrady lens distortion (lens_distortion.h): radial.xyz = k1, k2, k3; tangential.xy = p1, p2; all zero =
// none (radial.w = 1 when any coefficient is set, so kernels test one float instead of five).
struct LensDistortion {
  vec4 radial;
  vec4 tangential;
};

// Pinhole camera (docs/OPTICS.md §9 M0), optionally through a distorting lens.
struct PinholeParams {
  mat4 cameraToWorld;  // camera looks down -z, +y up
  vec4 lens;           // x tan(fovy/2), y aspect (W/H), z image width (px), w image height (px)
  LensDistortion distortion;
};

HT_SHARED_END
#endif
