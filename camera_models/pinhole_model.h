// pinhole_model.h - pinhole camera rays (shared C++/GLSL), model M0 of docs/OPTICS.md §9.
//
//   d_cam = ((2(x+xi_x)/W - 1)*aspect*tan(fovy/2), (2(y+xi_y)/H - 1)*tan(fovy/2), -1),  o = eye
//
// Pixel (x, y) with y counted from the BOTTOM (docs/OPTICS.md §0), xi in [0,1)^2 the sample position inside the pixel.
// The camera looks down -z with +y up; cameraToWorld maps camera space to world (column 3 = eye).
// Through a distorting lens (p.distortion, lens_distortion.h) the pixel's normalized image point
// ((2(x+xi_x)/W - 1)*aspect*tan(fovy/2), (2(y+xi_y)/H - 1)*tan(fovy/2)) is the distorted point x_d; the ray leaves
// along the undistorted one u (distort(u) = x_d): d_cam = (u.x, u.y, -1). A lens without distortion skips the
// inverse (one uniform branch).
#ifndef HT_PINHOLE_MODEL_H
#define HT_PINHOLE_MODEL_H
#include "common/glsl_cpp.h"
#include "camera_models/camera_params.h"
#include "camera_models/lens_distortion.h"

HT_SHARED_BEGIN

HT_INLINE void pinhole_ray(PinholeParams p, uint x, uint y, vec2 xi, HT_OUT(vec3) origin, HT_OUT(vec3) dir) {
  float tanHalfFovy = p.lens.x;
  float aspect = p.lens.y;
  float sx = 2.0f * (float(x) + xi.x) / p.lens.z - 1.0f;
  float sy = 2.0f * (float(y) + xi.y) / p.lens.w - 1.0f;
  vec2 u = vec2(sx * aspect * tanHalfFovy, sy * tanHalfFovy);
  if (lens_has_distortion(p.distortion)) u = brown_conrady_undistort(p.distortion, u);
  origin = vec3(p.cameraToWorld[3]);
  dir = normalize(mat3(p.cameraToWorld) * vec3(u.x, u.y, -1.0f));
}

HT_SHARED_END
#endif  // HT_PINHOLE_MODEL_H
