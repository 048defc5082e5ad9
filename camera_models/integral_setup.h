// integral_setup.h - from an "integral" display config to the GPU block of the microlens model (integral_params.h,
// consumed by integral_model.h), and a double-precision reference written independently of the float code.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "camera_models/display_config.h"
#include "camera_models/integral_params.h"
#include "camera_models/lenticular_reference.h"  // ReferenceRay
#include "camera_models/screen_placement.h"
#include "scene/scene.h"

namespace ht {

// The panel (W*pp x H*pp display units) placed in the scene (screen_placement.h). Throws ConfigError if the config
// is not an integral display.
ScreenPlacement resolveIntegralPlacement(const DisplayConfig& config, const Bounds3& sceneBounds);
gpu_shared::IntegralParams makeIntegralParams(const DisplayConfig& config, const Bounds3& sceneBounds);

// docs/OPTICS.md §9 M4 in double (formulas and sources in integral_model.h).
class IntegralReference {
 public:
  IntegralReference(const DisplayConfig& config, const Bounds3& sceneBounds);
  glm::dvec2 pixelPosition(std::uint32_t x, std::uint32_t y, glm::dvec2 f) const;
  glm::dvec2 lensCentre(glm::dvec2 q) const;
  // Distance of q from the border of its lens cell, in lens pitches (0 on the border, 0.5 at the centre): where two
  // lenses meet, float and double may each pick either, and both are right.
  double lensBorderDistance(glm::dvec2 q) const;
  // The LCD point a sample of (x, y, view) at xi starts from (pixel or stripe subpixel, integral_model.h).
  glm::dvec2 samplePosition(std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::dvec2 xi) const;
  // view 0, 1, 2 = R, G, B stripe subpixel, anything else = whole pixel (integral_model.h integral_in_pixel).
  ReferenceRay ray(std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::dvec2 xi) const;

 private:
  IntegralConfig integral_;
  ScreenPlacement placement_;
  glm::dmat2 rotation_{1.0};
};

}  // namespace ht
