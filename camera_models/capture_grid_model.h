// capture_grid_model.h - two-plane capture grid rays (shared C++/GLSL), model M5 of docs/OPTICS.md §9.
//
// Light slab of Levoy & Hanrahan, "Light Field Rendering", SIGGRAPH 1996: a ray is the line through (s, t) on the
// camera plane and (u, v) on the focal plane; docs/OPTICS.md §9 M5 writes o = (s, t, 0), d = normalize(u - s, v - t,
// F). Here (display-local, as M1) the camera plane is z = distance and the focal window is z = 0, so
//   camera (i, j), view = j*columns + i (bottom-left first, like quilt views):
//     s = (i - (columns-1)/2)*ds,  t = (j - (rows-1)/2)*dt,  o = (s, t, distance)
//   pixel (x, y) (y from the bottom), xi in [0,1)^2:
//     P = (((x+xi_x)/W - 0.5)*windowW, ((y+xi_y)/H - 0.5)*windowH, 0),  d = normalize(P - o)
// A single row with ds = D tan(theta) spacing is the M1 quilt camera array generalised to 2D (full parallax).
#ifndef HT_CAPTURE_GRID_MODEL_H
#define HT_CAPTURE_GRID_MODEL_H
#include "common/glsl_cpp.h"
#include "camera_models/capture_grid_params.h"

HT_SHARED_BEGIN

HT_INLINE void capture_grid_ray(CaptureGridParams p, uint x, uint y, uint view, vec2 xi, HT_OUT(vec3) origin,
                                HT_OUT(vec3) dir) {
  uint columns = uint(p.grid.x);
  float i = float(view % columns), j = float(view / columns);
  vec3 o = vec3((i - 0.5f * float(p.grid.x - 1)) * p.geometry.x, (j - 0.5f * float(p.grid.y - 1)) * p.geometry.y,
                p.geometry.z);
  vec3 target = vec3(((float(x) + xi.x) / float(p.grid.z) - 0.5f) * p.window.x,
                     ((float(y) + xi.y) / float(p.grid.w) - 0.5f) * p.window.y, 0.0f);
  origin = vec3(p.localToWorld * vec4(o, 1.0f));
  dir = normalize(mat3(p.localToWorld) * normalize(target - o));
}

HT_SHARED_END
#endif  // HT_CAPTURE_GRID_MODEL_H
