// integral_config.h - the "integral" section of a display config (model "integral", docs/configs.md): an integral-
// imaging / microlens panel with full parallax (docs/OPTICS.md §7, §9 M4).
//
// Display units (e.g. mm), display-local frame (docs/OPTICS.md §0): lens array = plane z = 0 centred on the origin, LCD
// at z = -gap, viewer plane at z = +viewerDistance, +z toward the viewer.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "camera_models/json_fields.h"

namespace ht {

enum class LensSampling { Centre, Aperture };  // docs/OPTICS.md §7 "LensletCenter" / "LensletAverage"

struct IntegralConfig {
  std::uint32_t panelWidth = 0, panelHeight = 0;  // LCD pixels
  double pixelPitch = 0.0;                        // LCD pixel size, > 0 (square pixels)
  double lensPitch = 0.0;                         // lens spacing, > 0
  glm::dvec2 lensOffset{0.0};                     // a lens centre, relative to the panel centre
  double lensRotationDeg = 0.0;                   // lens grid rotation against the pixel grid, counter-clockwise
  double gap = 0.0;                               // LCD -> lens plane distance g, > 0
  double focalLength = 0.0;                       // lens focal length f, > 0
  double viewerDistance = 0.0;                    // lens plane -> viewer plane distance L, > 0
  // Rays start on the plane z = frontPlane (0 < frontPlane <= viewerDistance; default viewerDistance) and travel into
  // the display: scene content between that plane and the screen is in front of the screen (docs/OPTICS.md §7, §9 M4).
  double frontPlane = 0.0;
  LensSampling sampling = LensSampling::Centre;
};

// Parses and validates the section; `at` is its location ("integral"). Throws ConfigError.
IntegralConfig parseIntegral(const detail::JsonLocation& at, const nlohmann::json& section);

}  // namespace ht
