// oblique_setup.cpp - placement, ObliqueParams and the double reference of the oblique direction camera.
#include "camera_models/oblique_setup.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "camera_models/screen_placement.h"
#include "common/error.h"

namespace ht {

namespace {

constexpr double kZFrontMargin = 0.05;  // auto zFront: clearance beyond the bounds, fraction of the window size

const ObliqueConfig& requireOblique(const DisplayConfig& config) {
  if (config.model != DisplayModel::Oblique || !config.oblique)
    throw ConfigError(config.sourcePath, "model", "\"" + std::string(displayModelName(config.model)) + "\"",
                      "expected model \"oblique\" with an oblique section");
  return *config.oblique;
}

double degToRad(double deg) { return deg * std::numbers::pi / 180.0; }

}  // namespace

ObliqueGeometry resolveObliqueGeometry(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const ObliqueConfig& c = requireOblique(config);
  // Target and auto size exactly as the other models (camera.target / camera.size, screen_placement.h), with the
  // image as the "screen": world height = scale * imageHeight.
  const ScreenPlacement placement = resolveScreenPlacement(config, sceneBounds, c.imageWidth, c.imageHeight);
  ObliqueGeometry g;
  g.target = placement.target;
  g.windowWidth = c.windowWidth.value_or(placement.scale * c.imageWidth);
  g.windowHeight = c.windowHeight.value_or(placement.scale * c.imageHeight);
  if (c.zFront) {
    g.zFront = *c.zFront;
  } else {
    const double front = sceneBounds.empty() ? 0.0 : std::max(double(sceneBounds.hi.z) - g.target.z, 0.0);
    g.zFront = front + kZFrontMargin * std::max(g.windowWidth, g.windowHeight);
  }
  return g;
}

gpu_shared::ObliqueParams makeObliqueParams(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const ObliqueConfig& c = requireOblique(config);
  const ObliqueGeometry g = resolveObliqueGeometry(config, sceneBounds);
  gpu_shared::ObliqueParams p{};
  p.grid = glm::ivec4(static_cast<int>(c.columns), static_cast<int>(c.rows), static_cast<int>(c.imageWidth),
                      static_cast<int>(c.imageHeight));
  p.cone = glm::vec4(glm::dvec4(degToRad(c.horizontalConeDeg), degToRad(c.verticalConeDeg), g.zFront, 0.0));
  p.window = glm::vec4(glm::dvec4(g.windowWidth, g.windowHeight, 0.0, 0.0));
  p.localToWorld = glm::mat4(1.0f);
  p.localToWorld[3] = glm::vec4(glm::dvec4(g.target, 1.0));
  return p;
}

ObliqueReference::ObliqueReference(const DisplayConfig& config, const Bounds3& sceneBounds)
    : oblique_(requireOblique(config)), geometry_(resolveObliqueGeometry(config, sceneBounds)) {}

glm::dvec3 ObliqueReference::emissionDirection(std::uint32_t view) const {
  // Direction grid of docs/OPTICS.md §9 M6: angles evenly spaced at bin centres across the full cones.
  const double i = view % oblique_.columns, j = view / oblique_.columns;
  const double thx = degToRad(oblique_.horizontalConeDeg) * ((i + 0.5) / oblique_.columns - 0.5);
  const double thy = degToRad(oblique_.verticalConeDeg) * ((j + 0.5) / oblique_.rows - 0.5);
  return glm::normalize(glm::dvec3(std::tan(thx), std::tan(thy), 1.0));
}

glm::dvec3 ObliqueReference::windowPoint(std::uint32_t x, std::uint32_t y, glm::dvec2 xi) const {
  return geometry_.target + glm::dvec3(((x + xi.x) / oblique_.imageWidth - 0.5) * geometry_.windowWidth,
                                       ((y + xi.y) / oblique_.imageHeight - 0.5) * geometry_.windowHeight, 0.0);
}

ReferenceRay ObliqueReference::ray(std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::dvec2 xi) const {
  // Burnett's oblique view (docs/OPTICS.md §9 M6): o = X + e_k*(zFront/e_k.z), d = -e_k.
  const glm::dvec3 e = emissionDirection(view);
  return {windowPoint(x, y, xi) + e * (geometry_.zFront / e.z), -e};
}

}  // namespace ht
