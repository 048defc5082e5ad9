// projector_model.h - primary rays of an HPO projector array (shared C++/GLSL), model M3 of docs/OPTICS.md §9.
//
// Double-perspective (multiple-centre-of-projection) ray: horizontal direction from the projector, vertical
// perspective from the observer (Jones et al., SIGGRAPH 2007; planar form of wps1215/LightFieldDisplayModel
// RenderingNaive/RayTracer.cpp RenderProjector, docs/OPTICS.md §6):
//   S  = H_k (i + xi_x, j + xi_y, 1), dehomogenised, on the screen z = 0      (pixel (i, j), j from the bottom)
//   ox = S.x - (S.x - P_k.x)/P_k.z * Dobs                                      (line P_k -> S continued to z = Dobs)
//   o  = (ox, h, Dobs);  d = normalize(S - o)
// Display units are scaled to world units by p.scale.x, then placed by localToWorld. Screen scattering (docs/OPTICS.md
// §9 M3): projector_scattered_ray rotates the ray about the vertical axis through S by dA ~ N(0, sigma), sigma =
// angular_scattering/1.11741/sqrt(2) (from LightFieldInterpolation.cpp's weight exp(-dA^2*1.11741^2/as^2)).
#ifndef HT_PROJECTOR_MODEL_H
#define HT_PROJECTOR_MODEL_H
#include "common/glsl_cpp.h"
#include "camera_models/lens_distortion.h"
#include "camera_models/projector_params.h"

HT_SHARED_BEGIN

HT_CONST float HT_PROJECTOR_SCATTER_NORM = 1.11741f;  // LightFieldInterpolation.cpp
HT_CONST float HT_PROJECTOR_TWO_PI = 6.28318530717958647692f;

// One projector with the array's shared values. The kernels build it from single uniform members (raygen.comp) rather
// than pass the 8 KiB ProjectorArrayParams by value: a by-value struct indexed with a per-lane projector number would
// be copied to per-invocation scratch memory by the shader compiler.
struct ProjectorView {
  vec4 observer;      // as ProjectorArrayParams.observer
  vec4 scale;         // as ProjectorArrayParams.scale
  mat4 localToWorld;  // as ProjectorArrayParams.localToWorld
  mat4 projector;     // ProjectorArrayParams.projector[k]
  vec4 lens;          // as ProjectorArrayParams.lens
  LensDistortion distortion;
};

HT_INLINE ProjectorView projector_view(HT_IN(ProjectorArrayParams) p, uint view) {
  ProjectorView v;
  v.observer = p.observer;
  v.scale = p.scale;
  v.localToWorld = p.localToWorld;
  v.projector = p.projector[view];
  v.lens = p.lens;
  v.distortion = p.distortion;
  return v;
}

// Screen point (display units, z = 0) of projector position (px, py) in pixels (py from the bottom). Through a
// distorting lens the panel pixel p sits at the distorted image point: with principal point c (image centre +
// lens.zw) and focal length f = lens.x, the ideal pixel is c + f undistort((p - c)/f) (lens_distortion.h, OpenCV's
// camera model), and the homography maps ideal pixels, as a calibration on undistorted coordinates gives it.
HT_INLINE vec3 projector_screen_point(HT_IN(ProjectorView) v, vec2 pixel) {
  if (lens_has_distortion(v.distortion)) {
    vec2 c = 0.5f * vec2(v.projector[0].w, v.projector[1].w) + vec2(v.lens.z, v.lens.w);
    pixel = c + v.lens.x * brown_conrady_undistort(v.distortion, (pixel - c) / v.lens.x);
  }
  mat3 h = mat3(v.projector);
  vec3 s = h * vec3(pixel.x, pixel.y, 1.0f);
  return vec3(s.x / s.z, s.y / s.z, 0.0f);
}

// Display-local (unscaled) double-perspective ray through screen point s of the projector.
HT_INLINE void projector_local_ray(HT_IN(ProjectorView) v, vec3 s, HT_OUT(vec3) origin, HT_OUT(vec3) dir) {
  vec3 position = vec3(v.projector[3]);
  float observerDistance = v.observer.x;
  float ox = s.x - (s.x - position.x) / position.z * observerDistance;
  origin = vec3(ox, v.observer.y, observerDistance);
  dir = normalize(s - origin);
}

// Display-local -> world: positions scaled by scale.x then placed; directions rotated only.
HT_INLINE void projector_to_world(HT_IN(ProjectorView) v, HT_INOUT(vec3) origin, HT_INOUT(vec3) dir) {
  origin = vec3(v.localToWorld * vec4(origin * v.scale.x, 1.0f));
  dir = normalize(mat3(v.localToWorld) * dir);
}

// Primary ray of pixel (x, y) (y from the bottom) of the projector at footprint position xi in [0,1)^2.
HT_INLINE void projector_view_ray(HT_IN(ProjectorView) v, uint x, uint y, vec2 xi, HT_OUT(vec3) origin,
                                  HT_OUT(vec3) dir) {
  vec3 s = projector_screen_point(v, vec2(float(x) + xi.x, float(y) + xi.y));
  projector_local_ray(v, s, origin, dir);
  projector_to_world(v, origin, dir);
}

// As projector_view_ray, with the screen's horizontal scattering sampled by xiAngle in [0,1)^2 (Box-Muller normal
// draw): the ray is rotated about the vertical axis through S by dA, origin and direction alike (docs/OPTICS.md §9 M3).
HT_INLINE void projector_view_scattered_ray(HT_IN(ProjectorView) v, uint x, uint y, vec2 xi, vec2 xiAngle,
                                            HT_OUT(vec3) origin, HT_OUT(vec3) dir) {
  vec3 s = projector_screen_point(v, vec2(float(x) + xi.x, float(y) + xi.y));
  projector_local_ray(v, s, origin, dir);
  float sigma = v.observer.z / HT_PROJECTOR_SCATTER_NORM / sqrt(2.0f);
  float radius = sqrt(-2.0f * log(max(1.0f - xiAngle.x, 1e-30f)));
  float angle = sigma * radius * cos(HT_PROJECTOR_TWO_PI * xiAngle.y);
  float c = cos(angle), sn = sin(angle);
  vec3 arm = origin - s;  // rotation about +y through S
  origin = s + vec3(c * arm.x + sn * arm.z, arm.y, -sn * arm.x + c * arm.z);
  dir = vec3(c * dir.x + sn * dir.z, dir.y, -sn * dir.x + c * dir.z);
  projector_to_world(v, origin, dir);
}

// Whole-array conveniences (C++ callers and tests): projector `view` of the array.
HT_INLINE void projector_ray(HT_IN(ProjectorArrayParams) p, uint x, uint y, uint view, vec2 xi, HT_OUT(vec3) origin,
                             HT_OUT(vec3) dir) {
  projector_view_ray(projector_view(p, view), x, y, xi, origin, dir);
}
HT_INLINE void projector_scattered_ray(HT_IN(ProjectorArrayParams) p, uint x, uint y, uint view, vec2 xi, vec2 xiAngle,
                                       HT_OUT(vec3) origin, HT_OUT(vec3) dir) {
  projector_view_scattered_ray(projector_view(p, view), x, y, xi, xiAngle, origin, dir);
}

HT_SHARED_END
#endif  // HT_PROJECTOR_MODEL_H
