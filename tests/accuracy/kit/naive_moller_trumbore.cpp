#include "naive_moller_trumbore.h"

#include <algorithm>
#include <atomic>
#include <thread>

namespace ht::accuracy {

NaiveMollerTrumbore::NaiveMollerTrumbore(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                         MtVariant variant)
    : positions_(positions.begin(), positions.end()),
      triangles_(triangles.begin(), triangles.end()),
      bvh_(bvh::buildBinnedSah(positions, triangles, bvh::BuildOptions{})),
      variant_(variant) {
  // Pad every box by a relative 1e-5 of its extent (plus a tiny absolute term) so the control's box test is
  // conservative: every miss it reports is the triangle test's doing, not the traversal's.
  for (bvh::Bvh2Node& node : bvh_.nodes) {
    const glm::vec3 pad = 1e-5f * (node.hi - node.lo) + 1e-5f * glm::max(glm::abs(node.lo), glm::abs(node.hi));
    node.lo -= pad;
    node.hi += pad;
  }
}

bool NaiveMollerTrumbore::hitsTriangle(uint32_t tri, const gpu_shared::HtRay& ray) const {
  const glm::uvec3 idx = triangles_[tri];
  const glm::vec3 v0 = positions_[idx.x], e1 = positions_[idx.y] - v0, e2 = positions_[idx.z] - v0;
  const glm::vec3 p = glm::cross(ray.dir, e2);
  const float det = glm::dot(e1, p);
  const float epsilon = variant_ == MtVariant::Epsilon1em6 ? 1e-6f : 0.0f;
  if (std::abs(det) <= epsilon) return false;
  const float inv = 1.0f / det;
  const glm::vec3 s = ray.origin - v0;
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return false;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(ray.dir, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return false;
  const float t = glm::dot(e2, q) * inv;
  return t >= ray.tmin && t <= ray.tmax;
}

bool NaiveMollerTrumbore::hits(const gpu_shared::HtRay& ray) const {
  if (bvh_.nodes.empty()) return false;
  const glm::vec3 inv = 1.0f / ray.dir;  // IEEE: +-inf for zero components, which the slab form tolerates
  uint32_t stack[128];
  uint32_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const bvh::Bvh2Node& node = bvh_.nodes[stack[--top]];
    const glm::vec3 t0 = (node.lo - ray.origin) * inv, t1 = (node.hi - ray.origin) * inv;
    float tNear = ray.tmin, tFar = ray.tmax;
    for (int k = 0; k < 3; ++k) {
      const float a = std::min(t0[k], t1[k]), b = std::max(t0[k], t1[k]);
      if (!(a != a)) tNear = std::max(tNear, a);  // NaN (0 * inf on a slab plane) leaves the slab open
      if (!(b != b)) tFar = std::min(tFar, b);
    }
    if (tNear > tFar) continue;
    if (node.isLeaf()) {
      for (uint32_t i = 0; i < node.triCount; ++i) {
        if (hitsTriangle(bvh_.primIndex[node.leftFirst + i], ray)) return true;
      }
    } else if (top + 2 <= 128) {
      stack[top++] = node.leftFirst;
      stack[top++] = node.leftFirst + 1;
    }
  }
  return false;
}

uint64_t NaiveMollerTrumbore::countMisses(std::span<const gpu_shared::HtRay> rays) const {
  std::atomic<uint64_t> misses{0};
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < threads; ++w) {
    pool.emplace_back([&, w] {
      uint64_t local = 0;
      for (size_t i = w; i < rays.size(); i += threads) local += hits(rays[i]) ? 0 : 1;
      misses += local;
    });
  }
  for (std::thread& t : pool) t.join();
  return misses.load();
}

}  // namespace ht::accuracy
