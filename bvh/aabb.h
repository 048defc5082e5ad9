// aabb.h - axis-aligned bounding box used by the builder (host only).
#pragma once
#include <limits>

#include <glm/glm.hpp>

namespace ht::bvh {

struct Aabb {
  glm::vec3 lo{std::numeric_limits<float>::infinity()};
  glm::vec3 hi{-std::numeric_limits<float>::infinity()};

  void grow(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void grow(const Aabb& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  bool contains(const Aabb& b) const {
    return glm::all(glm::lessThanEqual(lo, b.lo)) && glm::all(glm::lessThanEqual(b.hi, hi));
  }
  // Half surface area dx*dy + dy*dz + dz*dx (the SAH only needs ratios); 0 for an empty box.
  float halfArea() const {
    if (empty()) return 0.0f;
    glm::vec3 d = hi - lo;
    return d.x * d.y + d.y * d.z + d.z * d.x;
  }
};

}  // namespace ht::bvh
