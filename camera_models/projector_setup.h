// projector_setup.h - from a "projector-array" display config to the GPU block of the HPO model (projector_params.h,
// consumed by projector_model.h), and a double-precision reference written independently of the float code.
#pragma once
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_reference.h"  // ReferenceRay
#include "camera_models/projector_params.h"
#include "camera_models/screen_placement.h"
#include "scene/scene.h"

namespace ht {

// Where the screen (Sw x Sh display units) sits in the scene (screen_placement.h).
using ProjectorPlacement = ScreenPlacement;
ProjectorPlacement resolveProjectorPlacement(const DisplayConfig& config, const Bounds3& sceneBounds);

// angularScattering, or "auto": 1.5 x the angle between the two central projectors (sorted by the horizontal angle
// atan(P.x / -P.z) seen from the screen centre; LightFieldDisplayModel GenerateSampleModels/main.cpp, docs/OPTICS.md
// §6).
double resolveAngularScattering(const ProjectorArrayConfig& array);

// The projector's pixel -> screen homography (its own, or the linear mapping), row-major.
std::array<double, 9> projectorHomography(const ProjectorArrayConfig& array, std::uint32_t k);

// Throws ConfigError if the config is not a projector-array display.
gpu_shared::ProjectorArrayParams makeProjectorArrayParams(const DisplayConfig& config, const Bounds3& sceneBounds);

// docs/OPTICS.md §9 M3 in double (see projector_model.h for the formulas and sources).
class ProjectorArrayReference {
 public:
  ProjectorArrayReference(const DisplayConfig& config, const Bounds3& sceneBounds);
  glm::dvec3 screenPoint(std::uint32_t projector, glm::dvec2 pixel) const;  // display units, z = 0
  ReferenceRay ray(std::uint32_t x, std::uint32_t y, std::uint32_t projector, glm::dvec2 xi) const;
  const ProjectorArrayConfig& array() const { return array_; }
  const ProjectorPlacement& placement() const { return placement_; }

 private:
  ProjectorArrayConfig array_;
  ProjectorPlacement placement_;
};

}  // namespace ht
