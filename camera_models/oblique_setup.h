// oblique_setup.h - from an "oblique" display config to the GPU block (oblique_params.h, consumed by
// oblique_model.h), and a double-precision reference written independently of the float code.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_reference.h"  // ReferenceRay
#include "camera_models/oblique_params.h"
#include "scene/scene.h"

namespace ht {

// The oblique camera placed in the scene (world units, world-aligned display-local frame at `target`).
struct ObliqueGeometry {
  glm::dvec3 target{0.0};  // window centre: camera.target, "auto" = bounds centre (origin if empty)
  double windowWidth = 0.0, windowHeight = 0.0;  // oblique.window, or "auto": height = camera.size / auto fit
                                                 // (screen_placement.h), width = height * imageWidth / imageHeight
  double zFront = 0.0;  // oblique.zFront, or "auto" = max(bounds.hi.z - target.z, 0) + 5% of the larger window side
};

// Throws ConfigError if the config is not an oblique display.
ObliqueGeometry resolveObliqueGeometry(const DisplayConfig& config, const Bounds3& sceneBounds);
gpu_shared::ObliqueParams makeObliqueParams(const DisplayConfig& config, const Bounds3& sceneBounds);

// docs/OPTICS.md §9 M6 in double (formulas and sources in oblique_model.h).
class ObliqueReference {
 public:
  ObliqueReference(const DisplayConfig& config, const Bounds3& sceneBounds);
  const ObliqueGeometry& geometry() const { return geometry_; }
  // Emission direction e_k of view k (unit, world = display-local axes); the ray direction is -e_k.
  glm::dvec3 emissionDirection(std::uint32_t view) const;
  // Window point X of a sample, world.
  glm::dvec3 windowPoint(std::uint32_t x, std::uint32_t y, glm::dvec2 xi) const;
  ReferenceRay ray(std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::dvec2 xi) const;

 private:
  ObliqueConfig oblique_;
  ObliqueGeometry geometry_;
};

}  // namespace ht
