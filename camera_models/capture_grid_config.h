// capture_grid_config.h - the "captureGrid" section of a display config (model "capture-grid", docs/configs.md): a
// regular camera array for offline light-field capture, two-plane (light slab) parametrisation (docs/OPTICS.md §9 M5).
//
// World units, display-local frame placed at camera.target (world-aligned axes): the focal window (u, v) is centred
// on the origin in the plane z = 0, the camera plane (s, t) is z = distance (toward the viewer, +z).
#pragma once
#include <cstdint>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "camera_models/json_fields.h"

namespace ht {

struct CaptureGridConfig {
  std::uint32_t columns = 0, rows = 0;            // cameras, [1, 1024] each
  glm::dvec2 spacing{0.0};                        // camera pitch in s and t (world units), > 0
  double distance = 0.0;                          // camera plane to focal plane (world units), > 0
  double windowWidth = 0.0, windowHeight = 0.0;   // focal window (shared (u, v) rectangle, world units), > 0
  std::uint32_t imageWidth = 0, imageHeight = 0;  // pixels per camera image
};

// Parses and validates the section; `at` is its location ("captureGrid"). Throws ConfigError.
CaptureGridConfig parseCaptureGrid(const detail::JsonLocation& at, const nlohmann::json& section);

}  // namespace ht
