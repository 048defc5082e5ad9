// integral_setup.cpp - placement, IntegralParams and the double reference of the microlens model.
#include "camera_models/integral_setup.h"

#include <cmath>
#include <numbers>

#include "camera_models/lenticular_params.h"  // splitPhaseRate
#include "common/error.h"

namespace ht {

namespace {

const IntegralConfig& requireIntegral(const DisplayConfig& config) {
  if (config.model != DisplayModel::Integral || !config.integral)
    throw ConfigError(config.sourcePath, "model", "\"" + std::string(displayModelName(config.model)) + "\"",
                      "expected model \"integral\" with an integral section");
  return *config.integral;
}

double rotationRad(const IntegralConfig& c) { return c.lensRotationDeg * std::numbers::pi / 180.0; }

}  // namespace

ScreenPlacement resolveIntegralPlacement(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const IntegralConfig& c = requireIntegral(config);
  return resolveScreenPlacement(config, sceneBounds, c.panelWidth * c.pixelPitch, c.panelHeight * c.pixelPitch);
}

gpu_shared::IntegralParams makeIntegralParams(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const IntegralConfig& c = requireIntegral(config);
  const ScreenPlacement placement = resolveIntegralPlacement(config, sceneBounds);
  gpu_shared::IntegralParams p{};
  p.panel = glm::vec4(
      glm::dvec4(c.panelWidth, c.panelHeight, c.pixelPitch, c.sampling == LensSampling::Aperture ? 1.0 : 0.0));
  p.lens = glm::vec4(glm::dvec4(c.lensPitch, c.focalLength, c.gap, c.frontPlane));
  p.grid = glm::vec4(glm::dvec4(c.lensOffset, std::cos(rotationRad(c)), std::sin(rotationRad(c))));
  p.scale = glm::vec4(static_cast<float>(placement.scale), 0.0f, 0.0f, 0.0f);
  p.localToWorld = glm::mat4(1.0f);
  p.localToWorld[3] = glm::vec4(glm::dvec4(placement.target, 1.0));
  // Lens-grid coordinates g = R^-1 (p - offset)/pitch, p = ((x + f.x - W/2)*pp, (y + f.y - H/2)*pp)
  // (integral_model.h): per-pixel rates A = R^-1 (pp, 0)/pitch, B = R^-1 (0, pp)/pitch and the corner value g0,
  // reduced mod 1 (only the position inside the lens cell is needed).
  const double cs = std::cos(rotationRad(c)), sn = std::sin(rotationRad(c)), k = c.pixelPitch / c.lensPitch;
  const glm::dvec2 a(cs * k, -sn * k), b(sn * k, cs * k);
  const glm::dvec2 corner(-0.5 * c.panelWidth * c.pixelPitch - c.lensOffset.x,
                          -0.5 * c.panelHeight * c.pixelPitch - c.lensOffset.y);
  const glm::dvec2 g0 = glm::dvec2(cs * corner.x + sn * corner.y, -sn * corner.x + cs * corner.y) / c.lensPitch;
  const glm::vec2 ax = splitPhaseRate(a.x, c.panelWidth), ay = splitPhaseRate(a.y, c.panelWidth);
  const glm::vec2 bx = splitPhaseRate(b.x, c.panelHeight), by = splitPhaseRate(b.y, c.panelHeight);
  p.rateX = glm::vec4(ax.x, ax.y, ay.x, ay.y);
  p.rateY = glm::vec4(bx.x, bx.y, by.x, by.y);
  p.gridConst = glm::vec4(glm::dvec4(g0 - glm::floor(g0), 0.0, 0.0));
  return p;
}

IntegralReference::IntegralReference(const DisplayConfig& config, const Bounds3& sceneBounds)
    : integral_(requireIntegral(config)), placement_(resolveIntegralPlacement(config, sceneBounds)) {
  const double a = rotationRad(integral_);
  rotation_ = glm::dmat2(std::cos(a), std::sin(a), -std::sin(a), std::cos(a));  // columns: counter-clockwise by a
}

glm::dvec2 IntegralReference::pixelPosition(std::uint32_t x, std::uint32_t y, glm::dvec2 f) const {
  return {(x + f.x - 0.5 * integral_.panelWidth) * integral_.pixelPitch,
          (y + f.y - 0.5 * integral_.panelHeight) * integral_.pixelPitch};
}

glm::dvec2 IntegralReference::lensCentre(glm::dvec2 q) const {
  // Lens index = round(R^-1 (q - offset) / pitch) (docs/OPTICS.md §7).
  const glm::dvec2 grid = glm::transpose(rotation_) * (q - integral_.lensOffset) / integral_.lensPitch;
  const glm::dvec2 index(std::floor(grid.x + 0.5), std::floor(grid.y + 0.5));
  return integral_.lensOffset + rotation_ * (index * integral_.lensPitch);
}

double IntegralReference::lensBorderDistance(glm::dvec2 q) const {
  const glm::dvec2 grid = glm::transpose(rotation_) * (q - integral_.lensOffset) / integral_.lensPitch;
  const glm::dvec2 rel = grid - glm::floor(grid + 0.5);  // [-0.5, 0.5)
  return 0.5 - std::max(std::fabs(rel.x), std::fabs(rel.y));
}

glm::dvec2 IntegralReference::samplePosition(std::uint32_t x, std::uint32_t y, std::uint32_t view,
                                             glm::dvec2 xi) const {
  const bool aperture = integral_.sampling == LensSampling::Aperture;
  const glm::dvec2 f = aperture ? glm::dvec2(0.5) : xi;
  return pixelPosition(x, y, view < 3 ? glm::dvec2((view + f.x) / 3.0, f.y) : f);
}

ReferenceRay IntegralReference::ray(std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::dvec2 xi) const {
  const bool aperture = integral_.sampling == LensSampling::Aperture;
  const glm::dvec2 pixel = samplePosition(x, y, view, xi);
  const glm::dvec2 c = lensCentre(pixel);
  const glm::dvec2 s = aperture ? c + rotation_ * ((xi - 0.5) * integral_.lensPitch) : c;
  // Thin lens, ray-transfer form (see integral_model.h): slope = (s - p)/g - (s - c)/f.
  const glm::dvec2 slope = (s - pixel) / integral_.gap - (s - c) / integral_.focalLength;
  const glm::dvec3 e = glm::normalize(glm::dvec3(slope, 1.0));
  const glm::dvec3 o = glm::dvec3(s, 0.0) + e * (integral_.frontPlane / e.z);
  return {placement_.target + placement_.scale * o, -e};
}

}  // namespace ht
