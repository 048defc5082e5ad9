// pinhole_model.h - pinhole camera rays (shared C++/GLSL), model M0 of optics.md §9.
//
//   d_cam = ((2(x+xi_x)/W - 1)*aspect*tan(fovy/2), (2(y+xi_y)/H - 1)*tan(fovy/2), -1),  o = eye
//
// Pixel (x, y) with y counted from the BOTTOM (optics.md §0), xi in [0,1)^2 the sample position inside the pixel.
// The camera looks down -z with +y up; cameraToWorld maps camera space to world (column 3 = eye).
#ifndef HT_PINHOLE_MODEL_H
#define HT_PINHOLE_MODEL_H
#include "common/glsl_cpp.h"
#include "camera_models/camera_params.h"

HT_SHARED_BEGIN

HT_INLINE void pinhole_ray(PinholeParams p, uint x, uint y, vec2 xi, HT_OUT(vec3) origin, HT_OUT(vec3) dir) {
  float tanHalfFovy = p.lens.x;
  float aspect = p.lens.y;
  float sx = 2.0f * (float(x) + xi.x) / p.lens.z - 1.0f;
  float sy = 2.0f * (float(y) + xi.y) / p.lens.w - 1.0f;
  vec3 d = vec3(sx * aspect * tanHalfFovy, sy * tanHalfFovy, -1.0f);
  origin = vec3(p.cameraToWorld[3]);
  dir = normalize(mat3(p.cameraToWorld) * d);
}

HT_SHARED_END
#endif  // HT_PINHOLE_MODEL_H
