// bvh_two_level_test.cpp - the two-level BVH returns the flattened BVH's closest hits bit for bit: random scenes of
// instanced meshes, random node moves (rigid, scaled, mirrored), ties, placements that make triangles degenerate or
// non-finite. Both are also checked against a brute-force loop over every triangle (least (t, id)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "bvh/build_primitives.h"
#include "bvh/bvh_layout_choice.h"
#include "bvh/cpu_traversal.h"
#include "bvh/offset_ray.h"
#include "bvh/two_level_bvh.h"
#include "bvh_test_util.h"
#include "common/error.h"
#include "instanced_soup.h"

namespace ht::bvh {
namespace {

using gpu_shared::HtHit;
using gpu_shared::HtRay;
using gpu_shared::HtTraceResult;
using test::InstancedSoup;
using test::Mesh;
using test::randomPlacement;
using test::randomRays;
using test::randomScene;

uint32_t bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}

// Least (t, id) over every usable triangle, each tested with the ray's own tmax.
HtHit bruteForce(const InstancedSoup& soup, const HtRay& ray) {
  HtHit best = gpu_shared::ht_trace_miss(ray).hit;
  if (!gpu_shared::ht_ray_is_valid(ray)) return best;
  const gpu_shared::HtWatertightRay r = gpu_shared::ht_make_watertight_ray(ray.origin, ray.dir, ray.tmin);
  for (const InstanceRange& range : soup.ranges) {
    for (uint32_t id = range.firstTriangle; id < range.firstTriangle + range.triangleCount; ++id) {
      const glm::uvec3& tri = soup.triangles[id];
      if (!isUsableTriangle(soup.positions, tri)) continue;
      float t, u, v;
      if (gpu_shared::ht_intersect_triangle(r, soup.positions[tri.x], soup.positions[tri.y], soup.positions[tri.z],
                                            ray.tmax, t, u, v) &&
          gpu_shared::ht_hit_precedes(t, id, best)) {
        best = HtHit{t, id, u, v};
      }
    }
  }
  return best;
}

::testing::AssertionResult sameHit(const HtHit& a, const HtHit& b) {
  if (a.triId == b.triId && bits(a.t) == bits(b.t) && bits(a.u) == bits(b.u) && bits(a.v) == bits(b.v))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(t " << a.t << ", id " << a.triId << ", u " << a.u << ", v " << a.v
                                       << ") vs (t " << b.t << ", id " << b.triId << ", u " << b.u << ", v " << b.v
                                       << ")";
}

// Two-level == flattened (rebuilt from scratch) == brute force, for every ray; returns the number of hits.
uint32_t expectSameHits(const InstancedSoup& soup, const TwoLevelBvh& twoLevel, const std::vector<HtRay>& rays,
                        bool withBruteForce) {
  const GpuBvh flat = buildGpuBvh(soup.positions, soup.triangles, BuildOptions{});
  uint32_t hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const HtTraceResult a = traceClosestTwoLevel(twoLevel, rays[i]);
    const HtTraceResult b = traceClosest(flat, rays[i]);
    EXPECT_FALSE(a.overflow || b.overflow) << "ray " << i;
    EXPECT_TRUE(sameHit(a.hit, b.hit)) << "ray " << i << ": two-level vs flattened";
    if (withBruteForce) { EXPECT_TRUE(sameHit(b.hit, bruteForce(soup, rays[i]))) << "ray " << i << ": vs brute force"; }
    hits += a.hit.triId != gpu_shared::HT_MISS;
  }
  return hits;
}

// Places `count` random instances (fewer when a pick repeats) anew and updates the two-level BVH; returns them.
std::vector<uint32_t> moveRandomInstances(std::mt19937& rng, InstancedSoup& soup, TwoLevelBvh& twoLevel,
                                          uint32_t count) {
  std::uniform_int_distribution<uint32_t> pick(0, static_cast<uint32_t>(soup.ranges.size() - 1));
  std::vector<uint32_t> moved;
  for (uint32_t k = 0; k < count; ++k) moved.push_back(pick(rng));
  std::sort(moved.begin(), moved.end());
  moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
  for (uint32_t m : moved) soup.place(m, randomPlacement(rng, true));
  twoLevel.updateInstances(soup.positions, soup.triangles, moved);
  return moved;
}

TEST(BvhTwoLevelTest, RandomScenesAndMovesMatchTheFlattenedBvhBitForBit) {
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    std::mt19937 rng(seed);
    InstancedSoup soup = randomScene(rng, 6 + 3 * seed);
    TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
    EXPECT_LE(twoLevel.shapeCount(), 3u);  // one tree shape per mesh, shared by its instances
    std::vector<HtRay> rays = randomRays(rng, soup, test::scaled(1500, 300));
    EXPECT_GT(expectSameHits(soup, twoLevel, rays, true), rays.size() / 10);

    for (int move = 0; move < 4; ++move) {
      moveRandomInstances(rng, soup, twoLevel, move % 2 == 1 ? 2 : 1);
      EXPECT_GT(expectSameHits(soup, twoLevel, rays, move == 3), 0u) << "seed " << seed << " move " << move;
    }
  }
}

// The closest hit after a move from the hit before it and a walk that enters the moved instances alone (the hit
// before was on none of them) or the others only beyond it (it was on one): ordered_traversal.h
// ht_trace_two_level_after_moves, what trace_closest.comp does for a partial re-render's rays.
HtTraceResult closestAfterMoves(const TwoLevelBvh& twoLevel, const HtRay& ray, const HtHit& kept, bool keptMoved,
                                const std::vector<uint32_t>& moved) {
  glm::uvec4 ids(~0u);
  for (size_t k = 0; k < moved.size(); ++k) ids[static_cast<int>(k)] = moved[k];
  const gpu_shared::TwoLevelView view = twoLevel.view();
  const HtTraceResult r = gpu_shared::ht_trace_two_level_after_moves(
      view, view.blas, ray, gpu_shared::HT_TRAVERSAL_STEP_LIMIT, kept, true, keptMoved, ids, 0u);
  EXPECT_FALSE(r.overflow);
  return r;
}

bool onInstances(const InstancedSoup& soup, const HtHit& hit, const std::vector<uint32_t>& instances) {
  return std::any_of(instances.begin(), instances.end(), [&](uint32_t i) {
    return hit.triId - soup.ranges[i].firstTriangle < soup.ranges[i].triangleCount;
  });
}

struct WalkCounts {
  uint32_t nowOnMoved = 0;  // rays whose hit before was on no moved instance and now is on one
  uint32_t keptMoved = 0;   // rays whose hit before was on a moved instance
  uint64_t walkSteps = 0;   // ... their steps from that hit
  uint64_t wholeSteps = 0;  // ... and in a whole trace
};

// Every ray: the walk from its hit before the move gives the whole trace's hit of the moved scene bit for bit.
WalkCounts expectWalksOfMovedInstancesMatch(const InstancedSoup& soup, const TwoLevelBvh& twoLevel,
                                            const std::vector<HtRay>& rays, const std::vector<HtTraceResult>& before,
                                            const std::vector<uint32_t>& moved) {
  WalkCounts counts;
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool keptMoved = onInstances(soup, before[i].hit, moved);
    const HtTraceResult whole = traceClosestTwoLevel(twoLevel, rays[i]);
    const HtTraceResult walked = closestAfterMoves(twoLevel, rays[i], before[i].hit, keptMoved, moved);
    EXPECT_TRUE(sameHit(walked.hit, whole.hit))
        << "ray " << i << (keptMoved ? " (hit before on a moved instance)" : "");
    if (keptMoved) {
      ++counts.keptMoved;
      counts.walkSteps += walked.steps;
      counts.wholeSteps += whole.steps;
    } else {
      counts.nowOnMoved += onInstances(soup, whole.hit, moved);
    }
  }
  return counts;
}

// Four random instanced scenes from seeds seedBase + 1..4, each moved four times (one random instance, then two, in
// turn): `before(twoLevel, rays)` runs before each move, `after(soup, twoLevel, rays, what before returned, moved)`
// after it.
template <class Before, class After>
void forEachRandomMove(uint32_t seedBase, const Before& before, const After& after) {
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    std::mt19937 rng(seedBase + seed);
    InstancedSoup soup = randomScene(rng, 6 + 2 * seed);
    TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
    const std::vector<HtRay> rays = randomRays(rng, soup, test::scaled(1500, 300));
    for (int move = 0; move < 4; ++move) {
      const auto state = before(twoLevel, rays);
      const std::vector<uint32_t> moved = moveRandomInstances(rng, soup, twoLevel, move % 2 == 1 ? 2 : 1);
      after(soup, twoLevel, rays, state, moved);
    }
  }
}

TEST(BvhTwoLevelTest, ClosestHitAfterMovesFromTheKeptHitAndTheMovedInstancesAlone) {
  WalkCounts all;
  forEachRandomMove(
      100,
      [](const TwoLevelBvh& twoLevel, const std::vector<HtRay>& rays) {
        return traceClosestTwoLevelBatch(twoLevel, rays);
      },
      [&](const InstancedSoup& soup, const TwoLevelBvh& twoLevel, const std::vector<HtRay>& rays,
          const std::vector<HtTraceResult>& before, const std::vector<uint32_t>& moved) {
        const WalkCounts c = expectWalksOfMovedInstancesMatch(soup, twoLevel, rays, before, moved);
        all.nowOnMoved += c.nowOnMoved;
        all.keptMoved += c.keptMoved;
        all.walkSteps += c.walkSteps;
        all.wholeSteps += c.wholeSteps;
      });
  // The walks found hits in front of kept ones (736 of them with 1,500 rays, 100 with 300).
  EXPECT_GT(all.nowOnMoved, test::scaled(300, 40));
  // Rays whose hit was on a moved instance walked the others beyond it, in fewer steps than whole traces.
  EXPECT_GT(all.keptMoved, test::scaled(300, 40));
  EXPECT_LT(all.walkSteps, all.wholeSteps);
  std::printf("[ walks ] %u rays from a hit on a moved instance: %llu steps, %llu traced whole\n", all.keptMoved,
              static_cast<unsigned long long>(all.walkSteps), static_cast<unsigned long long>(all.wholeSteps));
}

// A partial re-render's shadow rays that were unoccluded before a move walk the moved instances alone
// (ht_trace_two_level_any_after_moves, trace_any.comp): occluded exactly when the whole any-hit walk of the moved scene
// is, in fewer steps.
TEST(BvhTwoLevelTest, OcclusionAfterMovesOfRaysUnoccludedBeforeComesFromTheMovedInstancesAlone) {
  uint32_t unoccludedBefore = 0, nowOccluded = 0;
  uint64_t walkSteps = 0, wholeSteps = 0;
  auto occluded = [](const TwoLevelBvh& twoLevel, const HtRay& ray) {
    const gpu_shared::TwoLevelView view = twoLevel.view();
    return gpu_shared::ht_trace_two_level_any(view, view.blas, ray, gpu_shared::HT_TRAVERSAL_STEP_LIMIT);
  };
  forEachRandomMove(
      300,
      [&](const TwoLevelBvh& twoLevel, const std::vector<HtRay>& rays) {
        std::vector<bool> wasOccluded(rays.size());
        for (size_t i = 0; i < rays.size(); ++i)
          wasOccluded[i] = occluded(twoLevel, rays[i]).hit.triId != gpu_shared::HT_MISS;
        return wasOccluded;
      },
      [&](const InstancedSoup&, const TwoLevelBvh& twoLevel, const std::vector<HtRay>& rays,
          const std::vector<bool>& wasOccluded, const std::vector<uint32_t>& moved) {
        glm::uvec4 ids(~0u);
        for (size_t k = 0; k < moved.size(); ++k) ids[static_cast<int>(k)] = moved[k];
        const gpu_shared::TwoLevelView view = twoLevel.view();
        for (size_t i = 0; i < rays.size(); ++i) {
          if (wasOccluded[i]) continue;
          ++unoccludedBefore;
          const HtTraceResult whole = occluded(twoLevel, rays[i]);
          const HtTraceResult walked = gpu_shared::ht_trace_two_level_any_after_moves(
              view, view.blas, rays[i], gpu_shared::HT_TRAVERSAL_STEP_LIMIT, true, ids, 0u);
          ASSERT_FALSE(whole.overflow || walked.overflow) << "ray " << i;
          EXPECT_EQ(walked.hit.triId != gpu_shared::HT_MISS, whole.hit.triId != gpu_shared::HT_MISS) << "ray " << i;
          nowOccluded += whole.hit.triId != gpu_shared::HT_MISS;
          walkSteps += walked.steps;
          wholeSteps += whole.steps;
        }
      });
  EXPECT_GT(unoccludedBefore, test::scaled(1000, 200));
  EXPECT_GT(nowOccluded, test::scaled(100, 10));  // the moves occluded some of them
  EXPECT_LT(walkSteps, wholeSteps);
  std::printf("[ walks ] %u rays unoccluded before a move, %u occluded after: %llu steps, %llu walked whole\n",
              unoccludedBefore, nowOccluded, static_cast<unsigned long long>(walkSteps),
              static_cast<unsigned long long>(wholeSteps));
}

// A ray leaving the surface of one of `soup`'s instances `instance` (a sphere, convex) from a random point, offset
// as shade.comp offsets shadow rays, on the outside (`outward`) or into it; half run to infinity, half stop short.
HtRay rayLeavingInstance(std::mt19937& rng, const InstancedSoup& soup, uint32_t instance, bool outward) {
  const InstanceRange& range = soup.ranges[instance];
  const size_t vertices = soup.meshes[static_cast<size_t>(range.mesh)].positions.size();
  glm::dvec3 centroid(0.0);
  for (size_t v = 0; v < vertices; ++v) centroid += glm::dvec3(soup.positions[soup.firstVertex[instance] + v]);
  centroid /= static_cast<double>(vertices);
  std::uniform_int_distribution<uint32_t> pick(range.firstTriangle, range.firstTriangle + range.triangleCount - 1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), length(0.05f, 6.0f);
  const glm::uvec3 tri = soup.triangles[pick(rng)];
  const glm::vec3 p0 = soup.positions[tri.x], p1 = soup.positions[tri.y], p2 = soup.positions[tri.z];
  float u = unit(rng), v = unit(rng);
  if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
  const glm::vec3 p = (1.0f - u - v) * p0 + u * p1 + v * p2;
  glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  if ((glm::dot(glm::dvec3(n), glm::dvec3(p) - centroid) < 0.0) == outward) n = -n;
  glm::vec3 dir = test::randomUnitVector(rng);
  if (glm::dot(dir, n) < 0.0f) dir = -dir;
  return test::makeRay(gpu_shared::ht_offset_ray(p, n), dir, 0.0f, unit(rng) < 0.5f ? INFINITY : length(rng));
}

// Rays that leave a convex instance on its outside skip it (shade.comp marks shadow and bounce rays; docs/BVH.md
// §9.6): its bottom level on the two-level BVH (ht_trace_two_level_any_leaving, _ordered_leaving), its tagged
// triangles on the flattened one (ht_trace_any_leaving, ht_trace_closest_ordered_leaving). No point of a convex
// instance lies beyond the plane such a ray leaves, so the occlusion and the closest hit are the whole walk's, bit for
// bit, in fewer steps. Rays into the instance (which shade never marks) show that the skip is real: the whole walk
// meets the instance, the skipping walks never do.
TEST(BvhTwoLevelTest, RaysLeavingAConvexInstanceOnItsOutsideSkipItWithTheSameHits) {
  std::mt19937 rng(606);
  uint32_t outward = 0, occluded = 0, inward = 0;
  uint64_t skippingSteps = 0, wholeSteps = 0;
  const uint32_t raysPerInstance = test::scaled(150, 30);
  for (int scene = 0; scene < 4; ++scene) {
    const InstancedSoup soup = test::randomScene(rng, 24);
    const TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
    GpuBvh flat = buildGpuBvh(soup.positions, soup.triangles, BuildOptions{});
    std::vector<uint32_t> parts(soup.triangles.size(), 0u);  // the spheres (mesh 1 is a random soup)
    for (uint32_t i = 0; i < soup.ranges.size(); ++i)
      if (soup.ranges[i].mesh != 1)
        std::fill_n(parts.begin() + soup.ranges[i].firstTriangle, soup.ranges[i].triangleCount, i + 1);
    tagTriangleParts(flat, parts);
    const gpu_shared::TwoLevelView view = twoLevel.view();
    const gpu_shared::BvhView flatView{flat.nodes.data(), flat.triangles.data()};
    constexpr uint32_t kLimit = gpu_shared::HT_TRAVERSAL_STEP_LIMIT;
    for (uint32_t i = 0; i < soup.ranges.size(); ++i) {
      if (soup.ranges[i].mesh == 1) continue;
      const auto onInstance = [&](const HtTraceResult& r) {
        return r.hit.triId != gpu_shared::HT_MISS && parts[r.hit.triId] == i + 1;
      };
      for (uint32_t k = 0; k < raysPerInstance; ++k) {
        const bool out = k % 4 != 0;
        const HtRay ray = rayLeavingInstance(rng, soup, i, out);
        const HtTraceResult whole = gpu_shared::ht_trace_two_level_any(view, view.blas, ray, kLimit);
        const HtTraceResult skipping = gpu_shared::ht_trace_two_level_any_leaving(view, view.blas, ray, kLimit, i + 1);
        const HtTraceResult flatSkipping = gpu_shared::ht_trace_any_leaving(flatView, ray, kLimit, i + 1);
        const HtTraceResult closest = gpu_shared::ht_trace_two_level_ordered(view, view.blas, ray, kLimit);
        const HtTraceResult closestSkipping =
            gpu_shared::ht_trace_two_level_ordered_leaving(view, view.blas, ray, kLimit, i + 1);
        const HtTraceResult flatClosestSkipping =
            gpu_shared::ht_trace_closest_ordered_leaving(flatView, ray, kLimit, i + 1);
        ASSERT_FALSE(whole.overflow || skipping.overflow || flatSkipping.overflow || closest.overflow ||
                     closestSkipping.overflow || flatClosestSkipping.overflow)
            << "instance " << i << " ray " << k;
        EXPECT_FALSE(onInstance(skipping) || onInstance(flatSkipping) || onInstance(closestSkipping) ||
                     onInstance(flatClosestSkipping))
            << "instance " << i << " ray " << k;
        EXPECT_EQ(std::memcmp(&closestSkipping.hit, &flatClosestSkipping.hit, sizeof(HtHit)), 0)
            << "instance " << i << " ray " << k;
        if (!out) {  // into the sphere: the whole walk meets it (where the ray is long enough)
          inward += onInstance(whole);
          continue;
        }
        ++outward;
        const bool isOccluded = whole.hit.triId != gpu_shared::HT_MISS;
        EXPECT_EQ(skipping.hit.triId != gpu_shared::HT_MISS, isOccluded) << "instance " << i << " ray " << k;
        EXPECT_EQ(flatSkipping.hit.triId != gpu_shared::HT_MISS, isOccluded) << "instance " << i << " ray " << k;
        EXPECT_EQ(std::memcmp(&closestSkipping.hit, &closest.hit, sizeof(HtHit)), 0)
            << "instance " << i << " ray " << k;
        occluded += isOccluded;
        skippingSteps += skipping.steps + closestSkipping.steps;
        wholeSteps += whole.steps + closest.steps;
      }
    }
  }
  EXPECT_GT(occluded, outward / 20);  // other instances stand in the way of some
  EXPECT_GT(inward, test::scaled(400, 80));
  EXPECT_LT(skippingSteps, wholeSteps);
  std::printf("[ convex ] %u rays leaving a sphere, %u occluded: %llu steps skipping it, %llu walking it\n", outward,
              occluded, static_cast<unsigned long long>(skippingSteps), static_cast<unsigned long long>(wholeSteps));
}

// A moved instance placed exactly onto an unmoved one of the same mesh: every hit is a tie in t, and the least
// triangle id must win whether it belongs to the kept hit or to the walk.
TEST(BvhTwoLevelTest, ClosestHitAfterAMoveOntoAnotherInstanceKeepsTheLeastTriangleId) {
  for (const uint32_t movedInstance : {0u, 1u}) {
    InstancedSoup soup;
    soup.meshes.push_back(test::closedSphere(glm::vec3(0.0f), 1.0f, 8, 12));
    const glm::dmat4 here = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, -0.25, 0.125));
    const glm::dmat4 away = glm::translate(glm::dmat4(1.0), glm::dvec3(40.0, 0.0, 0.0));
    soup.add(0, movedInstance == 0 ? away : here);
    soup.add(0, movedInstance == 1 ? away : here);
    TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
    std::mt19937 rng(9);
    const std::vector<HtRay> rays = randomRays(rng, soup, 600);
    const std::vector<HtTraceResult> before = traceClosestTwoLevelBatch(twoLevel, rays);
    soup.place(movedInstance, here);
    const std::vector<uint32_t> moved{movedInstance};
    twoLevel.updateInstances(soup.positions, soup.triangles, moved);
    const uint32_t nowOnMoved = expectWalksOfMovedInstancesMatch(soup, twoLevel, rays, before, moved).nowOnMoved;
    // Instance 0 has the lower triangle ids: moved onto instance 1 it takes every tie; moved onto by it, none.
    if (movedInstance == 0) {
      EXPECT_GT(nowOnMoved, 50u);
    } else {
      EXPECT_EQ(nowOnMoved, 0u);
    }
  }
}

// Two coincident instances of one mesh, the one with the lower triangle ids then moved away: every hit before the
// move was on it (ties go to the least id), and every hit after it is on the other instance at the same t. The walk
// enters the unmoved instance only beyond the hit before the move, so that bound must not cull a hit at equal t.
TEST(BvhTwoLevelTest, ClosestHitAfterAMoveOffACoincidentInstanceFindsTheOtherAtTheSameT) {
  InstancedSoup soup;
  soup.meshes.push_back(test::closedSphere(glm::vec3(0.0f), 1.0f, 8, 12));
  const glm::dmat4 here = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, -0.25, 0.125));
  soup.add(0, here);
  soup.add(0, here);
  TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
  std::mt19937 rng(11);
  const std::vector<HtRay> rays = randomRays(rng, soup, 600);
  const std::vector<HtTraceResult> before = traceClosestTwoLevelBatch(twoLevel, rays);
  soup.place(0, glm::translate(glm::dmat4(1.0), glm::dvec3(40.0, 0.0, 0.0)));
  const std::vector<uint32_t> moved{0u};
  twoLevel.updateInstances(soup.positions, soup.triangles, moved);
  const WalkCounts c = expectWalksOfMovedInstancesMatch(soup, twoLevel, rays, before, moved);
  EXPECT_GT(c.keptMoved, 50u);
  uint32_t sameT = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    if (onInstances(soup, before[i].hit, moved))
      sameT += traceClosestTwoLevel(twoLevel, rays[i]).hit.t == before[i].hit.t;
  }
  EXPECT_EQ(sameT, c.keptMoved) << "the other instance lies exactly where the moved one was";
}

TEST(BvhTwoLevelTest, CoincidentInstancesTieAndTheLeastTriangleIdWins) {
  InstancedSoup soup;
  soup.meshes.push_back(test::closedSphere(glm::vec3(0.0f), 1.0f, 8, 12));
  const glm::dmat4 place = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, -0.25, 0.125));
  soup.add(0, place);
  soup.add(0, place);  // the same triangles again: every hit is a tie in t
  TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
  std::mt19937 rng(7);
  const std::vector<HtRay> rays = randomRays(rng, soup, 600);
  uint32_t hits = 0;
  for (const HtRay& ray : rays) {
    const HtTraceResult r = traceClosestTwoLevel(twoLevel, ray);
    if (r.hit.triId == gpu_shared::HT_MISS) continue;
    ++hits;
    EXPECT_LT(r.hit.triId, soup.ranges[1].firstTriangle) << "a tie must go to the first instance's triangle";
  }
  EXPECT_GT(hits, 50u);
  expectSameHits(soup, twoLevel, rays, true);
}

TEST(BvhTwoLevelTest, PlacementsThatBreakOrRestoreTrianglesStayExact) {
  std::mt19937 rng(11);
  InstancedSoup soup = randomScene(rng, 5);
  TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
  const std::vector<HtRay> rays = randomRays(rng, soup, 900);
  // A vertex of instance 1 becomes NaN and two of instance 2's triangles collapse onto a line.
  soup.positions[soup.firstVertex[1]] = glm::vec3(NAN);
  const glm::uvec3 tri = soup.triangles[soup.ranges[2].firstTriangle];
  soup.positions[tri.z] = soup.positions[tri.x] * 0.5f + soup.positions[tri.y] * 0.5f;
  soup.positions[tri.z] = soup.positions[tri.x];
  const std::vector<uint32_t> moved{1, 2};
  twoLevel.updateInstances(soup.positions, soup.triangles, moved);
  expectSameHits(soup, twoLevel, rays, true);
  // Restored placements bring the triangles back (instance 2's shape no longer covers them: a new shape).
  soup.place(1, randomPlacement(rng, false));
  soup.place(2, randomPlacement(rng, false));
  twoLevel.updateInstances(soup.positions, soup.triangles, moved);
  expectSameHits(soup, twoLevel, rays, true);
}

// A triangle degenerate in the build placement stays in the shape (a rotation can make a triangle exactly degenerate
// in one placement only): usable again after a move, it is traced without building another shape.
TEST(BvhTwoLevelTest, TriangleDegenerateAtBuildIsTracedOnceUsableWithoutANewShape) {
  std::mt19937 rng(5);
  InstancedSoup soup = randomScene(rng, 4);
  const glm::uvec3 tri = soup.triangles[soup.ranges[0].firstTriangle];
  soup.positions[tri.y] = soup.positions[tri.x];  // degenerate at build time
  TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
  const size_t shapesBefore = twoLevel.shapeCount();
  soup.place(0, randomPlacement(rng, false));
  const std::vector<uint32_t> moved{0};
  twoLevel.updateInstances(soup.positions, soup.triangles, moved);
  EXPECT_EQ(twoLevel.shapeCount(), shapesBefore);
  const std::vector<HtRay> rays = randomRays(rng, soup, 900);
  expectSameHits(soup, twoLevel, rays, true);
}

// A triangle with a NaN corner at build time has no box in the shape; once finite it is traced through a shape that
// holds it (another instance's of the same mesh, or a new one).
TEST(BvhTwoLevelTest, TriangleNonFiniteAtBuildIsTracedOnceFinite) {
  std::mt19937 rng(6);
  InstancedSoup soup = randomScene(rng, 4);
  soup.positions[soup.triangles[soup.ranges[0].firstTriangle].z] = glm::vec3(INFINITY, 0.0f, 0.0f);
  TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
  const size_t shapesBefore = twoLevel.shapeCount();
  soup.place(0, randomPlacement(rng, false));
  const std::vector<uint32_t> moved{0};
  twoLevel.updateInstances(soup.positions, soup.triangles, moved);
  EXPECT_LE(twoLevel.shapeCount(), shapesBefore + 1);
  const std::vector<HtRay> rays = randomRays(rng, soup, 900);
  expectSameHits(soup, twoLevel, rays, true);
}

TEST(BvhTwoLevelTest, OverlappingRangesAreRefused) {
  std::mt19937 rng(3);
  InstancedSoup soup = randomScene(rng, 2);
  std::vector<InstanceRange> ranges = soup.ranges;
  ranges[1].firstTriangle -= 1;
  EXPECT_THROW(TwoLevelBvh(soup.positions, soup.triangles, ranges), ht::SceneError);
  ranges = soup.ranges;
  ranges[1].triangleCount += 1;
  EXPECT_THROW(TwoLevelBvh(soup.positions, soup.triangles, ranges), ht::SceneError);
}

TEST(BvhTwoLevelTest, EmptyAndUncoveredScenesMiss) {
  InstancedSoup soup;
  soup.meshes.push_back(test::closedSphere(glm::vec3(0.0f), 1.0f, 6, 8));
  soup.add(0, glm::dmat4(1.0));
  const std::vector<InstanceRange> none;
  TwoLevelBvh empty(soup.positions, soup.triangles, none);
  EXPECT_EQ(traceClosestTwoLevel(empty, test::makeRay(glm::vec3(0, 0, 5), glm::vec3(0, 0, -1))).hit.triId,
            gpu_shared::HT_MISS);
  TwoLevelBvh full(soup.positions, soup.triangles, soup.ranges);
  EXPECT_NE(traceClosestTwoLevel(full, test::makeRay(glm::vec3(0, 0, 5), glm::vec3(0, 0, -1))).hit.triId,
            gpu_shared::HT_MISS);
}

}  // namespace
}  // namespace ht::bvh

namespace ht::bvh {
namespace {

TEST(BvhLayoutChoiceTest, MovedScenesUseTwoLevelStaticScenesTheCheaperLayout) {
  EXPECT_EQ(chooseBvhLayout(true, LayoutCosts{10.0, 50.0}), BvhLayout::TwoLevel);
  EXPECT_EQ(chooseBvhLayout(false, LayoutCosts{10.0, 50.0}), BvhLayout::Flattened);
  EXPECT_EQ(chooseBvhLayout(false, LayoutCosts{50.0, 10.0}), BvhLayout::TwoLevel);
  EXPECT_EQ(chooseBvhLayout(false, LayoutCosts{10.0, 10.0}), BvhLayout::Flattened);
}

TEST(BvhLayoutChoiceTest, OverlappingInstancesMeasureCostlierThanTheFlattenedBvh) {
  // Eight copies of a sphere shifted by a fraction of its radius: the instance boxes overlap heavily, which is
  // where a second level loses (every overlapping instance is entered).
  InstancedSoup soup;
  soup.meshes.push_back(test::closedSphere(glm::vec3(0.0f), 1.0f, 16, 24));
  for (int i = 0; i < 8; ++i) soup.add(0, glm::translate(glm::dmat4(1.0), glm::dvec3(0.05 * i, 0.03 * i, 0.0)));
  const TwoLevelBvh twoLevel(soup.positions, soup.triangles, soup.ranges);
  const GpuBvh flat = buildGpuBvh(soup.positions, soup.triangles, BuildOptions{});
  Aabb bounds;
  for (const glm::vec3& p : soup.positions) bounds.grow(p);
  const std::vector<HtRay> probes = layoutProbeRays(bounds, 1024);
  ASSERT_EQ(probes.size(), 1024u);
  EXPECT_EQ(std::memcmp(probes.data(), layoutProbeRays(bounds, 1024).data(), probes.size() * sizeof(HtRay)), 0);
  const LayoutCosts costs = measureLayoutCosts(flat, twoLevel, probes);
  EXPECT_GT(costs.twoLevelStepsPerRay, costs.flattenedStepsPerRay);
  EXPECT_EQ(chooseBvhLayout(false, costs), BvhLayout::Flattened);
}

}  // namespace
}  // namespace ht::bvh
