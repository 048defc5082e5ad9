// bvh_embree_test.cpp - differential test against Embree 3 (RTC_SCENE_FLAG_ROBUST) on the glmark2 bunny with
// 1024^2 pinhole rays, plus the single-thread throughput of the shared traversal next to rtcIntersect1.
#include <chrono>
#include <cmath>
#include <cstdio>

#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include "bench/embree_ray.h"
#include "bvh/cpu_traversal.h"
#include "bvh_test_util.h"

namespace ht::bvh {
namespace {

using gpu_shared::HT_MISS;

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  explicit EmbreeScene(const test::Mesh& mesh) {
    device = rtcNewDevice(nullptr);
    scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), mesh.positions.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      for (int k = 0; k < 3; ++k) vertices[3 * i + k] = mesh.positions[i][k];
    }
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), mesh.triangles.size()));
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      for (int k = 0; k < 3; ++k) indices[3 * i + k] = mesh.triangles[i][k];
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCRayHit intersect(const HtRay& ray, RTCIntersectContext& context) const {
    RTCRayHit rh = ht::embree::toEmbreeRayHit(ray);
    rtcIntersect1(scene, &context, &rh);
    return rh;
  }
};

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(BvhEmbree, BunnyPrimaryRaysAgreeWithRobustEmbree) {
  test::Mesh bunny = test::loadObj(test::kBunnyPath);
  if (bunny.triangles.empty()) GTEST_SKIP() << test::kBunnyPath << " not found";
  const uint32_t res = test::scaled(1024, 256);
  std::vector<HtRay> rays = test::pinholeRays(bunny, res, res);
  GpuBvh gpu = buildGpuBvh(bunny.positions, bunny.triangles, {});
  EmbreeScene embree(bunny);

  // Ours: single thread (the figure to report), then all cores through the batch API.
  std::vector<HtTraceResult> ours(rays.size());
  auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < rays.size(); ++i) ours[i] = traceClosest(gpu, rays[i]);
  const double oursSeconds = secondsSince(start);
  start = std::chrono::steady_clock::now();
  std::vector<HtTraceResult> batch = traceClosestBatch(gpu, rays);
  const double batchSeconds = secondsSince(start);

  std::vector<RTCRayHit> theirs(rays.size());
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < rays.size(); ++i) theirs[i] = embree.intersect(rays[i], context);
  const double embreeSeconds = secondsSince(start);

  uint64_t disagreements = 0, hitsOurs = 0, hitsEmbree = 0, tOver1e4 = 0, stepsSum = 0;
  uint32_t stepsMax = 0;
  double maxRelT = 0.0;
  for (size_t i = 0; i < rays.size(); ++i) {
    ASSERT_FALSE(ours[i].overflow);
    ASSERT_EQ(batch[i].hit.triId, ours[i].hit.triId);
    ASSERT_EQ(batch[i].hit.t, ours[i].hit.t);
    stepsSum += ours[i].steps;
    stepsMax = std::max(stepsMax, ours[i].steps);
    const bool weHit = ours[i].hit.triId != HT_MISS;
    const bool theyHit = theirs[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
    hitsOurs += weHit;
    hitsEmbree += theyHit;
    if (weHit != theyHit) {
      if (++disagreements <= 20) {
        std::printf("  disagreement ray %zu (px %zu,%zu): ours %s t=%.9g tri %u, embree %s t=%.9g tri %u\n", i, i % res,
                    i / res, weHit ? "hit" : "miss", ours[i].hit.t, ours[i].hit.triId, theyHit ? "hit" : "miss",
                    theirs[i].ray.tfar, theirs[i].hit.primID);
      }
      continue;
    }
    if (!weHit) continue;
    double rel = std::fabs(double(ours[i].hit.t) - theirs[i].ray.tfar) / theirs[i].ray.tfar;
    maxRelT = std::max(maxRelT, rel);
    tOver1e4 += rel > 1e-4;
  }
  const double mrays = [](size_t n, double s) { return static_cast<double>(n) / s * 1e-6; }(rays.size(), 1.0);
  std::printf(
      "  %ux%u rays: hits ours %llu, embree %llu, hit/miss disagreements %llu, max rel dt %.3g, "
      "dt > 1e-4: %llu\n",
      res, res, static_cast<unsigned long long>(hitsOurs), static_cast<unsigned long long>(hitsEmbree),
      static_cast<unsigned long long>(disagreements), maxRelT, static_cast<unsigned long long>(tOver1e4));
  std::printf("  steps per ray: mean %.1f, max %u (limit %u)\n", double(stepsSum) / rays.size(), stepsMax,
              gpu_shared::HT_TRAVERSAL_STEP_LIMIT);
  std::printf(
      "  Mrays/s: ours 1 thread %.2f, ours batch (%u threads) %.2f, embree rtcIntersect1 1 thread %.2f "
      "(ratio 1 thread %.2f)\n",
      mrays / oursSeconds, std::thread::hardware_concurrency(), mrays / batchSeconds, mrays / embreeSeconds,
      embreeSeconds / oursSeconds);
  EXPECT_LE(static_cast<double>(disagreements), 1e-5 * static_cast<double>(rays.size()));
  EXPECT_GT(hitsOurs, rays.size() / 10);
}

}  // namespace
}  // namespace ht::bvh
