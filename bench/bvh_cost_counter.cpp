// bvh_cost_counter.cpp - see bvh_cost_counter.h.
#include "bench/bvh_cost_counter.h"

#include <algorithm>
#include <atomic>
#include <limits>

#include "bench/parallel_tiles.h"
#include "bvh/watertight_triangle.h"

namespace ht::bench {
namespace {

using gpu_shared::HtRay;
constexpr std::size_t kChunk = 1024;

struct SlabRay {
  glm::vec3 origin, invDir;
  float tmin;
};

// Entry distance of the ray into the node's box within [tmin, tmax], or +inf if it misses.
float boxEntry(const SlabRay& r, const bvh::Bvh2Node& n, float tmax) {
  const glm::vec3 t0 = (n.lo - r.origin) * r.invDir, t1 = (n.hi - r.origin) * r.invDir;
  const glm::vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
  const float enter = std::max(std::max(near.x, near.y), std::max(near.z, r.tmin));
  const float exit = std::min(std::min(far.x, far.y), std::min(far.z, tmax));
  return enter <= exit ? enter : std::numeric_limits<float>::infinity();
}

struct Counter {
  const bvh::Bvh2& tree;
  std::span<const glm::vec3> positions;
  std::span<const glm::uvec3> triangles;
  bool anyHit;
  TraversalCost cost;

  // Tests the leaf's triangles; returns true when an any-hit query may stop.
  bool testLeaf(const bvh::Bvh2Node& leaf, const gpu_shared::HtWatertightRay& wr, float& tmax, bool& hit) {
    for (std::uint32_t k = 0; k < leaf.triCount; ++k) {
      const glm::uvec3 tri = triangles[tree.primIndex[leaf.leftFirst + k]];
      float t, u, v;
      cost.triangleTests++;
      if (gpu_shared::ht_intersect_triangle(wr, positions[tri.x], positions[tri.y], positions[tri.z], tmax, t, u, v)) {
        tmax = t;
        hit = true;
        if (anyHit) return true;
      }
    }
    return false;
  }

  // Returns the ray's loop iterations.
  std::uint64_t trace(const HtRay& ray) {
    const SlabRay sr{ray.origin, 1.0f / ray.dir, ray.tmin};
    const gpu_shared::HtWatertightRay wr = gpu_shared::ht_make_watertight_ray(ray.origin, ray.dir, ray.tmin);
    float tmax = ray.tmax;
    bool hit = false;
    std::uint32_t stack[128];
    std::uint32_t sp = 0, cur = 0;
    cost.rays++;
    std::uint64_t steps = 1;  // the root box test
    if (boxEntry(sr, tree.nodes[0], tmax) == std::numeric_limits<float>::infinity()) return steps;
    for (;; ++steps) {
      const bvh::Bvh2Node& node = tree.nodes[cur];
      if (node.isLeaf()) {
        if (testLeaf(node, wr, tmax, hit)) break;
      } else {
        cost.nodeVisits++;
        const std::uint32_t a = node.leftFirst, b = node.leftFirst + 1;
        float ta = boxEntry(sr, tree.nodes[a], tmax), tb = boxEntry(sr, tree.nodes[b], tmax);
        const bool swap = tb < ta;
        const std::uint32_t nearChild = swap ? b : a, farChild = swap ? a : b;
        if (swap) std::swap(ta, tb);
        constexpr float kMissed = std::numeric_limits<float>::infinity();
        if (ta != kMissed) {
          if (tb != kMissed && sp < 128) stack[sp++] = farChild;
          cur = nearChild;
          continue;
        }
      }
      if (sp == 0) break;
      cur = stack[--sp];
    }
    if (hit) cost.hits++;
    return steps;
  }
};

void accumulate(std::atomic<std::uint64_t>* sums, const TraversalCost& c) {
  sums[0] += c.rays;
  sums[1] += c.nodeVisits;
  sums[2] += c.triangleTests;
  sums[3] += c.hits;
  sums[4] += c.steps;
  sums[5] += c.lockstep8;
}

}  // namespace

TraversalCost countTraversalCost(const bvh::Bvh2& tree, std::span<const glm::vec3> positions,
                                 std::span<const glm::uvec3> triangles, std::span<const HtRay> rays, bool anyHit,
                                 unsigned threads) {
  std::atomic<std::uint64_t> sums[6] = {0, 0, 0, 0, 0, 0};
  if (tree.nodes.empty()) return {};
  static_assert(kChunk % 8 == 0, "lane groups must not straddle chunks");
  forEachChunkParallel(rays.size(), kChunk, threads, [&](std::size_t begin, std::size_t end) {
    Counter counter{tree, positions, triangles, anyHit, {}};
    std::uint64_t groupMax = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint64_t steps = counter.trace(rays[i]);
      counter.cost.steps += steps;
      groupMax = std::max(groupMax, steps);
      if ((i - begin) % 8 == 7 || i + 1 == end) {
        counter.cost.lockstep8 += 8 * groupMax;
        groupMax = 0;
      }
    }
    accumulate(sums, counter.cost);
  });
  TraversalCost total;
  total.rays = sums[0].load();
  total.nodeVisits = sums[1].load();
  total.triangleTests = sums[2].load();
  total.hits = sums[3].load();
  total.steps = sums[4].load();
  total.lockstep8 = sums[5].load();
  return total;
}

}  // namespace ht::bench
