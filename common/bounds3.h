// bounds3.h - an axis-aligned box in world space. Scenes report their bounds with it and the display models place
// their cameras by it ("auto" targets and sizes, docs/configs.md), so it lives below both scene/ and camera_models/.
#pragma once
#include <limits>

#include <glm/glm.hpp>

namespace ht {

// Empty until extended: lo = +inf, hi = -inf.
struct Bounds3 {
  glm::vec3 lo{std::numeric_limits<float>::infinity()};
  glm::vec3 hi{-std::numeric_limits<float>::infinity()};
  void extend(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
  glm::vec3 extent() const { return hi - lo; }
};

}  // namespace ht
