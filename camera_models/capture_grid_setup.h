// capture_grid_setup.h - from a "capture-grid" display config to the GPU block (capture_grid_params.h, consumed by
// capture_grid_model.h), and a double-precision reference written independently of the float code.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "camera_models/capture_grid_params.h"
#include "camera_models/display_config.h"
#include "camera_models/lenticular_reference.h"  // ReferenceRay
#include "scene/scene.h"

namespace ht {

// The window centre: camera.target, "auto" = bounds centre (origin for empty bounds). Geometry is in world units.
glm::dvec3 resolveCaptureGridTarget(const DisplayConfig& config, const Bounds3& sceneBounds);

// Throws ConfigError if the config is not a capture-grid display.
gpu_shared::CaptureGridParams makeCaptureGridParams(const DisplayConfig& config, const Bounds3& sceneBounds);

// docs/OPTICS.md §9 M5 in double (formulas in capture_grid_model.h).
class CaptureGridReference {
 public:
  CaptureGridReference(const DisplayConfig& config, const Bounds3& sceneBounds);
  glm::dvec3 cameraPosition(std::uint32_t view) const;  // world
  ReferenceRay ray(std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::dvec2 xi) const;

 private:
  CaptureGridConfig grid_;
  glm::dvec3 target_{0.0};
};

}  // namespace ht
