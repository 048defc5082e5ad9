// capture_grid_setup.cpp - CaptureGridParams and the double reference of the two-plane capture grid.
#include "camera_models/capture_grid_setup.h"

#include "common/error.h"

namespace ht {

namespace {

const CaptureGridConfig& requireCaptureGrid(const DisplayConfig& config) {
  if (config.model != DisplayModel::CaptureGrid || !config.captureGrid)
    throw ConfigError(config.sourcePath, "model", "\"" + std::string(displayModelName(config.model)) + "\"",
                      "expected model \"capture-grid\" with a captureGrid section");
  return *config.captureGrid;
}

}  // namespace

glm::dvec3 resolveCaptureGridTarget(const DisplayConfig& config, const Bounds3& sceneBounds) {
  requireCaptureGrid(config);
  const bool hasArea = !sceneBounds.empty() && (sceneBounds.extent().x > 0.0f || sceneBounds.extent().y > 0.0f);
  return config.camera.target.value_or(hasArea ? 0.5 * (glm::dvec3(sceneBounds.lo) + glm::dvec3(sceneBounds.hi))
                                               : glm::dvec3(0.0));
}

gpu_shared::CaptureGridParams makeCaptureGridParams(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const CaptureGridConfig& c = requireCaptureGrid(config);
  gpu_shared::CaptureGridParams p{};
  p.grid = glm::ivec4(static_cast<int>(c.columns), static_cast<int>(c.rows), static_cast<int>(c.imageWidth),
                      static_cast<int>(c.imageHeight));
  p.geometry = glm::vec4(glm::dvec4(c.spacing, c.distance, 0.0));
  p.window = glm::vec4(glm::dvec4(c.windowWidth, c.windowHeight, 0.0, 0.0));
  p.localToWorld = glm::mat4(1.0f);
  p.localToWorld[3] = glm::vec4(glm::dvec4(resolveCaptureGridTarget(config, sceneBounds), 1.0));
  return p;
}

CaptureGridReference::CaptureGridReference(const DisplayConfig& config, const Bounds3& sceneBounds)
    : grid_(requireCaptureGrid(config)), target_(resolveCaptureGridTarget(config, sceneBounds)) {}

glm::dvec3 CaptureGridReference::cameraPosition(std::uint32_t view) const {
  const double i = view % grid_.columns, j = view / grid_.columns;
  return target_ + glm::dvec3((i - 0.5 * (grid_.columns - 1.0)) * grid_.spacing.x,
                              (j - 0.5 * (grid_.rows - 1.0)) * grid_.spacing.y, grid_.distance);
}

ReferenceRay CaptureGridReference::ray(std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::dvec2 xi) const {
  // Levoy & Hanrahan 1996 light slab (docs/OPTICS.md §9 M5): through (s, t) on the camera plane and (u, v) on the
  // window.
  const glm::dvec3 o = cameraPosition(view);
  const glm::dvec3 p = target_ + glm::dvec3(((x + xi.x) / grid_.imageWidth - 0.5) * grid_.windowWidth,
                                            ((y + xi.y) / grid_.imageHeight - 0.5) * grid_.windowHeight, 0.0);
  return {o, glm::normalize(p - o)};
}

}  // namespace ht
