// quilt_model.h - the Looking Glass quilt cameras (shared C++/GLSL), model M1 of docs/OPTICS.md §9.
//
// looking-glass-webxr src/LookingGlassXRDevice.ts onFrameStart (docs/OPTICS.md §4.3, §9 M1):
//   D = 0.5*targetDiam/tan(fovy/2);  theta_i = viewCone*((i + 0.5)/N - 0.5);  o_i = (D tan(theta_i), 0, D)
//   tile pixel (x, y) of w x h (y from the bottom), xi in [0,1)^2 inside the pixel:
//   P = (((x + xi_x)/w - 0.5)*aspect*targetDiam, ((y + xi_y)/h - 0.5)*targetDiam, 0);  d = normalize(P - o_i)
// View 0 is the leftmost camera and the bottom-left tile (docs/OPTICS.md §4.1); quilt_layout.h places tiles. The result
// is the lenticular model's lenticular_ray_for_phase at the bin centre t = (i + 0.5)/N (tests/camera_models).
#ifndef HT_QUILT_MODEL_H
#define HT_QUILT_MODEL_H
#include "common/glsl_cpp.h"
#include "camera_models/quilt_params.h"

HT_SHARED_BEGIN

// Ray of tile pixel (x, y) of view `view` (0 = leftmost) at footprint position xi.
HT_INLINE void quilt_ray(QuiltParams p, uint x, uint y, uint view, vec2 xi, HT_OUT(vec3) origin, HT_OUT(vec3) dir) {
  float focalDistance = p.camera.x;
  float size = p.camera.y;
  float aspect = p.camera.z;
  float theta = p.camera.w * ((float(view) + 0.5f) / p.views.x - 0.5f);
  vec3 o = vec3(focalDistance * tan(theta), 0.0f, focalDistance);
  float u = (float(x) + xi.x) / float(p.tiles.z);
  float v = (float(y) + xi.y) / float(p.tiles.w);
  vec3 target = vec3((u - 0.5f) * aspect * size, (v - 0.5f) * size, 0.0f);
  origin = vec3(p.localToWorld * vec4(o, 1.0f));
  dir = normalize(mat3(p.localToWorld) * normalize(target - o));
}

HT_SHARED_END
#endif  // HT_QUILT_MODEL_H
