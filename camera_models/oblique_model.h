// oblique_model.h - oblique (sheared orthographic) direction camera rays (shared C++/GLSL), model M6 of docs/OPTICS.md
// §9.
//
// Burnett, "Oblique Slice and Dice" (TLBurnett3/LightField Src/Renderer/README.md; docs/OPTICS.md §7, §9 M6): one image
// per emission direction e_k; for a window point X the ray is o = X + e_k*zFront', d = -e_k (all rays of a view are
// parallel, so each view is one coherent batch). Pixels are later scattered into the hogels/lenticules that emit e_k.
// Our parametrisation (display-local, docs/OPTICS.md §0):
//   view k = j*columns + i (bottom-left first, like quilt views):
//     thx_i = coneX*((i+0.5)/columns - 0.5),  thy_j = coneY*((j+0.5)/rows - 0.5)
//     e_k = normalize(tan(thx_i), tan(thy_j), 1)            (emission direction, out of the display)
//   pixel (x, y) (y from the bottom), xi in [0,1)^2:
//     X = (((x+xi_x)/W - 0.5)*windowW, ((y+xi_y)/H - 0.5)*windowH, 0)
//     o = X + e_k*(zFront/e_k.z) = X + zFront*(tan(thx_i), tan(thy_j), 1)   (starts on the plane z = zFront)
//     d = -e_k
// then o_w = localToWorld*o, d_w = mat3(localToWorld)*d. The second form of o is algebraically the first; it is used
// because it puts o.z = zFront exactly and avoids a division by e_k.z.
// GPU precision note: tan() is evaluated in the shader; Vulkan only bounds tan through sin/cos (absolute error), so
// the GPU direction may differ from the C++ one by ~1e-6 rad on hardware with approximate sin/cos.
#ifndef HT_OBLIQUE_MODEL_H
#define HT_OBLIQUE_MODEL_H
#include "common/glsl_cpp.h"
#include "camera_models/oblique_params.h"

HT_SHARED_BEGIN

// Tangents (tan(thx_i), tan(thy_j)) of view `view`'s emission direction, display-local.
HT_INLINE vec2 oblique_view_tangents(ObliqueParams p, uint view) {
  uint columns = uint(p.grid.x);
  float i = float(view % columns), j = float(view / columns);
  HT_PRECISE float thx = p.cone.x * ((i + 0.5f) / float(p.grid.x) - 0.5f);
  HT_PRECISE float thy = p.cone.y * ((j + 0.5f) / float(p.grid.y) - 0.5f);
  return vec2(tan(thx), tan(thy));
}

HT_INLINE void oblique_ray(ObliqueParams p, uint x, uint y, uint view, vec2 xi, HT_OUT(vec3) origin, HT_OUT(vec3) dir) {
  vec2 t = oblique_view_tangents(p, view);
  HT_PRECISE vec3 windowPoint = vec3(((float(x) + xi.x) / float(p.grid.z) - 0.5f) * p.window.x,
                                     ((float(y) + xi.y) / float(p.grid.w) - 0.5f) * p.window.y, 0.0f);
  HT_PRECISE vec3 o = windowPoint + p.cone.z * vec3(t.x, t.y, 1.0f);
  origin = vec3(p.localToWorld * vec4(o, 1.0f));
  dir = normalize(mat3(p.localToWorld) * -normalize(vec3(t.x, t.y, 1.0f)));
}

HT_SHARED_END
#endif  // HT_OBLIQUE_MODEL_H
