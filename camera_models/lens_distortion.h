// lens_distortion.h - Brown-Conrady lens distortion (shared C++/GLSL): radial k1, k2, k3 and tangential (decentring)
// p1, p2, on normalized image coordinates (x, y) = (X/Z, Y/Z) of a camera or projector.
//
// D. C. Brown, "Decentering Distortion of Lenses", Photogrammetric Engineering 32(3), 1966; in the form and sign
// convention of OpenCV's camera model (calib3d "Camera Calibration and 3D Reconstruction", cv::projectPoints,
// https://docs.opencv.org/3.4/d9/d0c/group__calib3d.html; NVIDIA DriveOS NvMediaLensDistortion states the same form):
//   r^2 = x^2 + y^2,  radial = 1 + k1 r^2 + k2 r^4 + k3 r^6
//   x_d = x*radial + 2 p1 x y + p2 (r^2 + 2 x^2)
//   y_d = y*radial + p1 (r^2 + 2 y^2) + 2 p2 x y
// Rays need the inverse (a pixel sits at a distorted point; its ray direction is the undistorted one): Newton's method
// on F(u) = distort(u) - x_d with the analytic Jacobian, started at u = x_d, fixed HT_UNDISTORT_ITERATIONS steps.
#ifndef HT_LENS_DISTORTION_H
#define HT_LENS_DISTORTION_H
#include "common/glsl_cpp.h"
#include "camera_models/camera_params.h"
#include "camera_models/pinhole_model.h"

HT_SHARED_BEGIN

HT_CONST int HT_UNDISTORT_ITERATIONS = 12;

// GPU block (std430-safe): radial.xyz = k1, k2, k3; tangential.xy = p1, p2. All zero = no distortion.
struct LensDistortion {
  vec4 radial;
  vec4 tangential;
};

HT_INLINE vec2 brown_conrady_distort(LensDistortion d, vec2 u) {
  float r2 = u.x * u.x + u.y * u.y;
  float radial = 1.0f + r2 * (d.radial.x + r2 * (d.radial.y + r2 * d.radial.z));
  float p1 = d.tangential.x, p2 = d.tangential.y;
  return vec2(u.x * radial + 2.0f * p1 * u.x * u.y + p2 * (r2 + 2.0f * u.x * u.x),
              u.y * radial + p1 * (r2 + 2.0f * u.y * u.y) + 2.0f * p2 * u.x * u.y);
}

// Undistorted point u with brown_conrady_distort(d, u) = xd (Newton; exact for zero coefficients).
HT_INLINE vec2 brown_conrady_undistort(LensDistortion d, vec2 xd) {
  float p1 = d.tangential.x, p2 = d.tangential.y;
  vec2 u = xd;
  for (int i = 0; i < HT_UNDISTORT_ITERATIONS; ++i) {
    float r2 = u.x * u.x + u.y * u.y;
    float radial = 1.0f + r2 * (d.radial.x + r2 * (d.radial.y + r2 * d.radial.z));
    float dRadial = d.radial.x + r2 * (2.0f * d.radial.y + 3.0f * r2 * d.radial.z);  // d radial / d r^2
    vec2 f = brown_conrady_distort(d, u) - xd;
    float jxx = radial + 2.0f * u.x * u.x * dRadial + 2.0f * p1 * u.y + 6.0f * p2 * u.x;
    float jxy = 2.0f * u.x * u.y * dRadial + 2.0f * p1 * u.x + 2.0f * p2 * u.y;
    float jyx = 2.0f * u.x * u.y * dRadial + 2.0f * p1 * u.x + 2.0f * p2 * u.y;
    float jyy = radial + 2.0f * u.y * u.y * dRadial + 6.0f * p1 * u.y + 2.0f * p2 * u.x;
    float det = jxx * jyy - jxy * jyx;
    if (abs(det) < 1e-12f) break;
    u -= vec2(jyy * f.x - jxy * f.y, -jyx * f.x + jxx * f.y) / det;
  }
  return u;
}

// Pinhole ray (pinhole_model.h, optics.md §9 M0) through a distorting lens: the pixel's normalized image point
// ((2(x+xi_x)/W - 1)*aspect*tan(fovy/2), (2(y+xi_y)/H - 1)*tan(fovy/2)) is the distorted point; the ray leaves along
// the undistorted one, d_cam = (u.x, u.y, -1).
HT_INLINE void pinhole_distorted_ray(PinholeParams p, LensDistortion distortion, uint x, uint y, vec2 xi,
                                     HT_OUT(vec3) origin, HT_OUT(vec3) dir) {
  float tanHalfFovy = p.lens.x;
  float sx = 2.0f * (float(x) + xi.x) / p.lens.z - 1.0f;
  float sy = 2.0f * (float(y) + xi.y) / p.lens.w - 1.0f;
  vec2 u = brown_conrady_undistort(distortion, vec2(sx * p.lens.y * tanHalfFovy, sy * tanHalfFovy));
  origin = vec3(p.cameraToWorld[3]);
  dir = normalize(mat3(p.cameraToWorld) * vec3(u.x, u.y, -1.0f));
}

HT_SHARED_END
#endif  // HT_LENS_DISTORTION_H
