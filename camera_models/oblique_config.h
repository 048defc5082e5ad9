// oblique_config.h - the "oblique" section of a display config (model "oblique", docs/configs.md): a grid of
// sheared orthographic views, one per emission direction (Burnett "Oblique Slice and Dice", docs/OPTICS.md §9 M6).
//
// World units, display-local frame placed at camera.target (world-aligned axes): the window is centred on the origin
// in the plane z = 0, rays start on the plane z = zFront (toward the viewer, +z) and travel into the scene.
#pragma once
#include <cstdint>
#include <optional>

#include <nlohmann/json_fwd.hpp>

#include "camera_models/json_fields.h"

namespace ht {

struct ObliqueConfig {
  std::uint32_t columns = 0, rows = 0;            // directions, [1, 1024] each
  double horizontalConeDeg = 0.0;                 // full horizontal angular range (degrees), [0, 180)
  double verticalConeDeg = 0.0;                   // full vertical angular range (degrees), [0, 180); 0 or rows 1 = HPO
  std::uint32_t imageWidth = 0, imageHeight = 0;  // pixels per view, [1, 32768]
  // Window size (world units, > 0); nullopt = "auto": height = camera.size (or the auto fit of screen_placement.h),
  // width = height * imageWidth / imageHeight.
  std::optional<double> windowWidth, windowHeight;
  std::optional<double> zFront;  // distance of the ray start plane in front of the window (world, > 0); nullopt = auto
};

// Parses and validates the section; `at` is its location ("oblique"). Throws ConfigError.
ObliqueConfig parseOblique(const detail::JsonLocation& at, const nlohmann::json& section);

}  // namespace ht
