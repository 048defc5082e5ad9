// lenticular_reference.cpp - double-precision lenticular model (see lenticular_reference.h for the formulas).
#include "camera_models/lenticular_reference.h"

#include <cmath>

namespace ht {

LenticularReference::LenticularReference(const DisplayConfig& config, const Bounds3& sceneBounds)
    : camera_(resolveLenticularCamera(config, sceneBounds)) {
  calibration_ = *config.calibration;  // resolveLenticularCamera has checked it is present
  shader_ = lenticularShaderValues(calibration_);
}

std::uint32_t LenticularReference::cell(std::uint32_t x, std::uint32_t y) const {
  // holoplaycore.js GetCellForPixel (docs/OPTICS.md §3.2); xPos = int(u*W) = x, yPos = int(v*H) = y.
  const std::size_t count = calibration_.subpixelCells.size();
  if (calibration_.cellPatternMode == 0 || count == 0) return 0;
  std::uint32_t cellIndex = 0;
  switch (calibration_.cellPatternMode) {
    case 1: cellIndex = (x % 2 == y % 2) ? 0 : 1; break;
    case 2: cellIndex = x % 2; break;
    case 3: cellIndex = (y + (x % 2) * 2) % 4; break;
    case 4: cellIndex = y % 2; break;
    default: break;
  }
  return static_cast<std::uint32_t>(cellIndex % count);
}

glm::dvec2 LenticularReference::sampleUV(std::uint32_t x, std::uint32_t y, std::uint32_t c, glm::dvec2 xi) const {
  const double width = calibration_.screenW, height = calibration_.screenH;
  const std::uint32_t channel = calibration_.flipSubp ? 2 - c : c;  // HoloPlayCore ri/bi
  const double u = (x + 0.5) / width, v = (y + 0.5) / height;
  glm::dvec2 centre;
  if (calibration_.cellPatternMode != 0 && !calibration_.subpixelCells.empty()) {
    glm::dvec2 offset = calibration_.subpixelCells[cell(x, y)].offset(channel);
    centre = {u + offset.x / width, v + offset.y / height};
  } else {
    centre = {u + channel * shader_.subp, v};
  }
  return {centre.x + (xi.x - 0.5) / (3.0 * width), centre.y + (xi.y - 0.5) / height};
}

double LenticularReference::viewPhase(std::uint32_t x, std::uint32_t y, std::uint32_t c, glm::dvec2 xi) const {
  const glm::dvec2 uv = sampleUV(x, y, c, xi);
  const double phi = (uv.x + uv.y * shader_.tilt) * shader_.pitch - shader_.center;
  const double f = phi - std::floor(phi);
  const double t = calibration_.invView ? 1.0 - f : f;
  return std::min(t, std::nextafter(1.0, 0.0));
}

ReferenceRay LenticularReference::rayForPhase(double t, glm::dvec2 uv) const {
  const double theta = camera_.viewConeRad * (t - 0.5);
  const glm::dvec3 o(camera_.focalDistance * std::tan(theta), 0.0, camera_.focalDistance);
  const double u = calibration_.flipImageX ? 1.0 - uv.x : uv.x;
  const double v = calibration_.flipImageY ? 1.0 - uv.y : uv.y;
  const glm::dvec3 target((u - 0.5) * camera_.aspect * camera_.size, (v - 0.5) * camera_.size, 0.0);
  return {camera_.target + o, glm::normalize(target - o)};
}

ReferenceRay LenticularReference::ray(std::uint32_t x, std::uint32_t y, std::uint32_t c, glm::dvec2 xi) const {
  return rayForPhase(viewPhase(x, y, c, xi), sampleUV(x, y, c, xi));
}

}  // namespace ht
