// lens_distortion_params.cpp - see lens_distortion_params.h. Formulas: lens_distortion.h (Brown 1966, OpenCV form).
#include "camera_models/lens_distortion_params.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "camera_models/json_fields.h"
#include "camera_models/lens_distortion.h"
#include "common/error.h"

namespace ht {

namespace {

constexpr int kFoldSteps = 4096;

std::string coefficientsText(const LensDistortionSettings& d) {
  return "{k1 " + detail::formatNumber(d.k1) + ", k2 " + detail::formatNumber(d.k2) + ", k3 " +
         detail::formatNumber(d.k3) + ", p1 " + detail::formatNumber(d.p1) + ", p2 " + detail::formatNumber(d.p2) + "}";
}

// Radial profile f(r) = r (1 + k1 r^2 + k2 r^4 + k3 r^6) and its slope f'(r) = 1 + 3 k1 r^2 + 5 k2 r^4 + 7 k3 r^6.
double radialProfile(const LensDistortionSettings& d, double r) {
  const double r2 = r * r;
  return r * (1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3)));
}
double radialSlope(const LensDistortionSettings& d, double r) {
  const double r2 = r * r;
  return 1.0 + r2 * (3.0 * d.k1 + r2 * (5.0 * d.k2 + r2 * 7.0 * d.k3));
}

// The undistorted radius whose image is `maxRadius`, walking out from the centre while the profile rises; a slope
// <= 0 first means a fold inside the image. The tangential terms are small beside the radial ones for real lenses
// and are covered by the round-trip check below.
void checkNoFold(const LensDistortionSettings& d, double maxRadius, const std::string& file, const std::string& field) {
  const double step = maxRadius / kFoldSteps;
  for (int i = 0; i <= 8 * kFoldSteps; ++i) {
    const double r = i * step;
    if (radialProfile(d, r) >= maxRadius) return;
    if (!(radialSlope(d, r) > 0.0)) {
      throw ConfigError(
          file, field, coefficientsText(d),
          "a lens that does not fold inside the image: the radial profile stops rising at normalized radius " +
              detail::formatNumber(r) + ", before the image corner's " + detail::formatNumber(maxRadius) +
              " (reduce |k1|, or fit k2/k3 so that 1 + 3 k1 r^2 + 5 k2 r^4 + 7 k3 r^6 > 0)");
    }
  }
  throw ConfigError(file, field, coefficientsText(d),
                    "a lens whose image reaches the corner's normalized radius " + detail::formatNumber(maxRadius) +
                        " within 8x that radius (the coefficients compress the image too strongly)");
}

}  // namespace

LensDistortionSettings parseLensDistortion(const detail::JsonLocation& at, const nlohmann::json& distortion) {
  detail::rejectUnknownKeys(at, distortion, {"k1", "k2", "k3", "p1", "p2"});
  const std::string expected =
      "expected a finite Brown-Conrady coefficient (OpenCV convention, normalized coordinates)";
  LensDistortionSettings d;
  for (auto [key, value] : {std::pair{"k1", &d.k1}, {"k2", &d.k2}, {"k3", &d.k3}, {"p1", &d.p1}, {"p2", &d.p2}}) {
    *value = detail::optionalNumber(at, distortion, key, false, expected).value_or(0.0);
  }
  return d;
}

glm::dvec2 undistortReference(const LensDistortionSettings& d, glm::dvec2 xd) {
  // Newton in double on F(u) = distort(u) - xd, Jacobian from the written-out formula (Brown 1966, OpenCV form).
  glm::dvec2 u = xd;
  for (int i = 0; i < 100; ++i) {
    const double r2 = u.x * u.x + u.y * u.y;
    const double radial = 1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
    const double dRadial = d.k1 + r2 * (2.0 * d.k2 + 3.0 * r2 * d.k3);
    const glm::dvec2 f(u.x * radial + 2.0 * d.p1 * u.x * u.y + d.p2 * (r2 + 2.0 * u.x * u.x) - xd.x,
                       u.y * radial + d.p1 * (r2 + 2.0 * u.y * u.y) + 2.0 * d.p2 * u.x * u.y - xd.y);
    if (std::fabs(f.x) + std::fabs(f.y) < 1e-16) break;
    const double a = radial + 2.0 * u.x * u.x * dRadial + 2.0 * d.p1 * u.y + 6.0 * d.p2 * u.x;
    const double b = 2.0 * u.x * u.y * dRadial + 2.0 * d.p1 * u.x + 2.0 * d.p2 * u.y;
    const double e = radial + 2.0 * u.y * u.y * dRadial + 6.0 * d.p1 * u.y + 2.0 * d.p2 * u.x;
    const double det = a * e - b * b;
    u -= glm::dvec2(e * f.x - b * f.y, -b * f.x + a * f.y) / det;
  }
  return u;
}

gpu_shared::LensDistortion makeLensDistortion(const LensDistortionSettings& lens, glm::dvec2 halfExtent,
                                              const std::string& file, const std::string& field) {
  gpu_shared::LensDistortion block{};
  if (!lens.any()) return block;
  const double maxRadius = glm::length(halfExtent);
  checkNoFold(lens, maxRadius, file, field);
  block.radial = glm::vec4(glm::dvec4(lens.k1, lens.k2, lens.k3, 1.0));
  block.tangential = glm::vec4(glm::dvec4(lens.p1, lens.p2, 0.0, 0.0));
  // The kernel's float Newton inverse must land back on every corner and edge midpoint of the image.
  const double hx = halfExtent.x, hy = halfExtent.y;
  for (const glm::dvec2 xd : {glm::dvec2(hx, hy), glm::dvec2(-hx, hy), glm::dvec2(hx, -hy), glm::dvec2(-hx, -hy),
                              glm::dvec2(hx, 0.0), glm::dvec2(0.0, hy), glm::dvec2(-hx, 0.0), glm::dvec2(0.0, -hy)}) {
    const glm::vec2 u = gpu_shared::brown_conrady_undistort(block, glm::vec2(xd));
    const double miss = glm::length(glm::dvec2(gpu_shared::brown_conrady_distort(block, u)) - xd);
    if (!(miss < 1e-5 * (1.0 + maxRadius))) {
      throw ConfigError(file, field, coefficientsText(lens),
                        "a lens the ray generator can invert: Newton's inverse misses the image point (" +
                            detail::formatNumber(xd.x) + ", " + detail::formatNumber(xd.y) + ") by " +
                            detail::formatNumber(miss) + " (tangential p1/p2 too strong for the radial terms?)");
    }
  }
  return block;
}

}  // namespace ht
