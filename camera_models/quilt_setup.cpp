// quilt_setup.cpp - QuiltParams and the double reference of the quilt cameras (see quilt_setup.h).
#include "camera_models/quilt_setup.h"

#include <cmath>

namespace ht {

gpu_shared::QuiltParams makeQuiltParams(const DisplayConfig& config, const Bounds3& sceneBounds,
                                        const QuiltLayout& layout) {
  const LenticularCamera camera = resolveLenticularCamera(config, sceneBounds);
  gpu_shared::QuiltParams p{};
  // looking-glass-webxr LookingGlassXRDevice.ts (docs/OPTICS.md §4.3): D, targetDiam, aspect, full viewCone in radians.
  p.camera = glm::vec4(glm::dvec4(camera.focalDistance, camera.size, layout.aspect, camera.viewConeRad));
  p.tiles = glm::ivec4(static_cast<int>(layout.columns), static_cast<int>(layout.rows),
                       static_cast<int>(layout.tileWidth), static_cast<int>(layout.tileHeight));
  p.views = glm::vec4(static_cast<float>(layout.views()), 0.0f, 0.0f, 0.0f);
  p.localToWorld = glm::mat4(1.0f);
  p.localToWorld[3] = glm::vec4(glm::dvec4(camera.target, 1.0));
  return p;
}

QuiltReference::QuiltReference(const DisplayConfig& config, const Bounds3& sceneBounds, const QuiltLayout& layout)
    : camera_(resolveLenticularCamera(config, sceneBounds)), layout_(layout) {}

ReferenceRay QuiltReference::ray(std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::dvec2 xi) const {
  const double theta = camera_.viewConeRad * ((view + 0.5) / layout_.views() - 0.5);
  const glm::dvec3 o(camera_.focalDistance * std::tan(theta), 0.0, camera_.focalDistance);
  const double u = (x + xi.x) / layout_.tileWidth, v = (y + xi.y) / layout_.tileHeight;
  const glm::dvec3 p((u - 0.5) * layout_.aspect * camera_.size, (v - 0.5) * camera_.size, 0.0);
  return {camera_.target + o, glm::normalize(p - o)};
}

}  // namespace ht
