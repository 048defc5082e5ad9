// pinhole_params.cpp - pinhole camera defaults and the PinholeParams block (docs/OPTICS.md §9 M0).
#include "camera_models/pinhole_params.h"

#include <cmath>
#include <numbers>

#include "camera_models/json_fields.h"
#include "camera_models/lens_distortion_params.h"
#include "camera_models/lenticular_params.h"
#include "common/error.h"

namespace ht {

namespace {

constexpr double kAutoFitMargin = 1.1;
constexpr double kFallbackHeight = 2.0;

std::string pointText(const glm::dvec3& p) {
  return "[" + detail::formatNumber(p.x) + ", " + detail::formatNumber(p.y) + ", " + detail::formatNumber(p.z) + "]";
}

bool hasArea(const Bounds3& bounds) {
  return !bounds.empty() && (bounds.extent().x > 0.0f || bounds.extent().y > 0.0f);
}

// Distance along +z from lookAt at which the bounds' x/y extent fills the view with 10 % margin, plus half the depth
// so the eye stays in front of the bounds.
double autoDistance(const Bounds3& bounds, double fovyRad, double aspect) {
  if (!hasArea(bounds)) return 0.5 * kFallbackHeight / std::tan(0.5 * fovyRad);
  glm::dvec3 extent = glm::dvec3(bounds.hi) - glm::dvec3(bounds.lo);
  double height = kAutoFitMargin * std::max(extent.y, extent.x / aspect);
  return 0.5 * height / std::tan(0.5 * fovyRad) + 0.5 * extent.z;
}

}  // namespace

PinholeCamera resolvePinholeCamera(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const bool lenticular = config.model == DisplayModel::Lenticular && config.calibration.has_value();
  PinholeCamera camera;
  if (lenticular) {
    camera.width = config.calibration->screenW;
    camera.height = config.calibration->screenH;
    camera.fovyDeg = config.camera.fovyDeg;
  }
  camera.width = config.pinhole.width.value_or(camera.width);
  camera.height = config.pinhole.height.value_or(camera.height);
  camera.fovyDeg = config.pinhole.fovyDeg.value_or(camera.fovyDeg);
  camera.up = config.pinhole.up;

  const LenticularCamera display = lenticular ? resolveLenticularCamera(config, sceneBounds) : LenticularCamera{};
  glm::dvec3 autoLookAt = glm::dvec3(0.0);
  if (lenticular) {
    autoLookAt = display.target;
  } else if (hasArea(sceneBounds)) {
    autoLookAt = glm::dvec3(sceneBounds.lo) + 0.5 * (glm::dvec3(sceneBounds.hi) - glm::dvec3(sceneBounds.lo));
  }
  camera.lookAt = config.pinhole.lookAt.value_or(autoLookAt);
  if (config.pinhole.eye) {
    camera.eye = *config.pinhole.eye;
  } else if (lenticular) {
    camera.eye = camera.lookAt + glm::dvec3(0.0, 0.0, display.focalDistance);
  } else {
    const double aspect = static_cast<double>(camera.width) / static_cast<double>(camera.height);
    const double fovy = camera.fovyDeg * std::numbers::pi / 180.0;
    camera.eye = camera.lookAt + glm::dvec3(0.0, 0.0, autoDistance(sceneBounds, fovy, aspect));
  }
  return camera;
}

gpu_shared::PinholeParams makePinholeParams(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const PinholeCamera camera = resolvePinholeCamera(config, sceneBounds);
  const glm::dvec3 view = camera.lookAt - camera.eye;
  if (!(glm::length(view) > 0.0))
    throw ConfigError(config.sourcePath, "pinhole.eye", pointText(camera.eye),
                      "expected an eye position different from lookAt " + pointText(camera.lookAt));
  const glm::dvec3 forward = glm::normalize(view);
  const glm::dvec3 side = glm::cross(forward, camera.up);
  if (!(glm::length(side) > 1e-9 * glm::length(camera.up)))
    throw ConfigError(config.sourcePath, "pinhole.up", pointText(camera.up),
                      "expected an up vector not parallel to the view direction " + pointText(forward));
  const glm::dvec3 right = glm::normalize(side);
  const glm::dvec3 up = glm::cross(right, forward);
  // Camera space: looks down -z, +y up (docs/OPTICS.md §9 M0); columns = right, up, -forward, eye.
  const glm::dmat4 cameraToWorld(glm::dvec4(right, 0.0), glm::dvec4(up, 0.0), glm::dvec4(-forward, 0.0),
                                 glm::dvec4(camera.eye, 1.0));
  const double fovy = camera.fovyDeg * std::numbers::pi / 180.0;
  gpu_shared::PinholeParams p{};
  p.cameraToWorld = glm::mat4(cameraToWorld);
  const double tanHalf = std::tan(0.5 * fovy), aspect = static_cast<double>(camera.width) / camera.height;
  p.lens =
      glm::vec4(glm::dvec4(tanHalf, aspect, static_cast<double>(camera.width), static_cast<double>(camera.height)));
  p.distortion = makeLensDistortion(config.pinhole.distortion, glm::dvec2(aspect * tanHalf, tanHalf), config.sourcePath,
                                    "pinhole.distortion");
  return p;
}

}  // namespace ht
