// pinhole_params.h - from a display config to the GPU parameter block of the pinhole model
// (camera_params.h PinholeParams, consumed by pinhole_model.h; docs/OPTICS.md §9 M0).
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "camera_models/camera_params.h"
#include "camera_models/display_config.h"
#include "scene/scene.h"

namespace ht {

// The pinhole camera resolved against the scene. Defaults (docs/configs.md, "pinhole"):
//   width x height: pinhole.width/height, else the panel size (lenticular config), else 1280 x 720;
//   fovy: pinhole.fovyDeg, else camera.fovyDeg (lenticular config), else 45 degrees;
//   lookAt: pinhole.lookAt, else the lenticular target, else the bounds centre (origin for empty bounds);
//   eye: pinhole.eye, else the centre view of the lenticular display (lookAt + (0, 0, D)), else on +z far enough
//        that the bounds' x/y extent fits with 10 % margin.
struct PinholeCamera {
  std::uint32_t width = 1280, height = 720;
  double fovyDeg = 45.0;
  glm::dvec3 eye{0.0}, lookAt{0.0}, up{0.0, 1.0, 0.0};
};
PinholeCamera resolvePinholeCamera(const DisplayConfig& config, const Bounds3& sceneBounds);

// Works for both models (a lenticular config gives its centre-view preview camera). Throws ConfigError when eye
// equals lookAt or up is parallel to the view direction.
gpu_shared::PinholeParams makePinholeParams(const DisplayConfig& config, const Bounds3& sceneBounds);

}  // namespace ht
