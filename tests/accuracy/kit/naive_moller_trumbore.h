// naive_moller_trumbore.h - the control of the watertightness tests: textbook Möller-Trumbore in float
// behind a plain BVH2 traversal, i.e. what a renderer without Woop's watertight test would do.
//
// Möller & Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection", JGT 2(1) 1997: det = e1 . (d x e2),
// u = (o - v0) . (d x e2) / det, v = d . ((o - v0) x e1) / det, t = e2 . ((o - v0) x e1) / det, accepted
// when u >= 0, v >= 0, u + v <= 1. The paper's code rejects |det| < EPSILON = 1e-6 (tinybvh's CPU version
// too, docs/BVH.md §5.4): an absolute threshold that depends on scale. Variant NoEpsilon rejects only det == 0.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh_builder.h"
#include "bvh/ray_types.h"

namespace ht::accuracy {

enum class MtVariant { Epsilon1em6, NoEpsilon };

class NaiveMollerTrumbore {
 public:
  NaiveMollerTrumbore(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles, MtVariant variant);
  // true when the ray hits some triangle in [tmin, tmax].
  bool hits(const gpu_shared::HtRay& ray) const;
  // Misses among `rays`, over all cores.
  uint64_t countMisses(std::span<const gpu_shared::HtRay> rays) const;

 private:
  bool hitsTriangle(uint32_t tri, const gpu_shared::HtRay& ray) const;
  std::vector<glm::vec3> positions_;
  std::vector<glm::uvec3> triangles_;
  bvh::Bvh2 bvh_;
  MtVariant variant_;
};

}  // namespace ht::accuracy
