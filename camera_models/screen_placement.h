// screen_placement.h - where a display whose geometry is given in display units (mm) sits in the scene:
// world = target + scale * local, world-aligned axes (display-local frame of docs/OPTICS.md §0).
#pragma once
#include <glm/glm.hpp>

#include "camera_models/display_config.h"
#include "scene/scene.h"

namespace ht {

struct ScreenPlacement {
  glm::dvec3 target{0.0};
  double scale = 1.0;  // world units per display unit
};

// camera.target "auto" = bounds centre (origin for empty bounds); camera.size = world height of the screen, "auto" =
// 1.1 * max(extent.y, extent.x / (screenWidth/screenHeight)) (2 for empty or flat bounds), as for the lenticular focal
// rectangle (lenticular_params.h).
ScreenPlacement resolveScreenPlacement(const DisplayConfig& config, const Bounds3& sceneBounds, double screenWidth,
                                       double screenHeight);

}  // namespace ht
