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
// on F(u) = distort(u) - x_d with the analytic Jacobian, started at u = x_d, until |F| is at float resolution or
// HT_UNDISTORT_ITERATIONS steps.
#ifndef HT_LENS_DISTORTION_H
#define HT_LENS_DISTORTION_H
#include "common/glsl_cpp.h"
#include "camera_models/camera_params.h"

HT_SHARED_BEGIN

HT_CONST int HT_UNDISTORT_ITERATIONS = 12;        // the most Newton steps
HT_CONST float HT_UNDISTORT_TOLERANCE = 1.0e-7f;  // |F(u)|_1 at which a step stops, relative to 1 + |x_d|_1

// The GPU block LensDistortion is in camera_params.h (radial.w = 1 marks a lens with distortion).
HT_INLINE bool lens_has_distortion(LensDistortion d) { return d.radial.w != 0.0f; }

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
    // Converged to float resolution (Newton doubles the correct digits each step: 3-5 steps for real lenses).
    if (abs(f.x) + abs(f.y) <= HT_UNDISTORT_TOLERANCE * (1.0f + abs(xd.x) + abs(xd.y))) break;
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

HT_SHARED_END
#endif  // HT_LENS_DISTORTION_H
