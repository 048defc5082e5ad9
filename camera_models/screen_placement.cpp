// screen_placement.cpp - see screen_placement.h.
#include "camera_models/screen_placement.h"

#include <algorithm>

namespace ht {

namespace {
constexpr double kAutoFitMargin = 1.1;
constexpr double kFallbackHeight = 2.0;
}  // namespace

ScreenPlacement resolveScreenPlacement(const DisplayConfig& config, const Bounds3& sceneBounds, double screenWidth,
                                       double screenHeight) {
  const bool hasArea = !sceneBounds.empty() && (sceneBounds.extent().x > 0.0f || sceneBounds.extent().y > 0.0f);
  const glm::dvec3 lo(sceneBounds.lo), hi(sceneBounds.hi);
  ScreenPlacement placement;
  placement.target = config.camera.target.value_or(hasArea ? 0.5 * (lo + hi) : glm::dvec3(0.0));
  const double aspect = screenWidth / screenHeight;
  const double autoHeight = hasArea ? kAutoFitMargin * std::max(hi.y - lo.y, (hi.x - lo.x) / aspect) : kFallbackHeight;
  placement.scale = config.camera.size.value_or(autoHeight) / screenHeight;
  return placement;
}

}  // namespace ht
