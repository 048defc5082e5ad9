#include "robust_embree.h"

#include <algorithm>
#include <thread>

#include <embree3/rtcore.h>

#include "bench/embree_ray.h"
#include "common/error.h"

namespace ht::accuracy {

struct RobustEmbree::Handles {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

RobustEmbree::RobustEmbree(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles)
    : handles_(std::make_unique<Handles>()) {
  handles_->device = rtcNewDevice(nullptr);
  if (handles_->device == nullptr) throw Error("Embree: rtcNewDevice failed");
  handles_->scene = rtcNewScene(handles_->device);
  rtcSetSceneFlags(handles_->scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(handles_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), positions.size()));
  for (size_t i = 0; i < positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) v[3 * i + k] = positions[i][k];
  }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), triangles.size()));
  for (size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) idx[3 * i + k] = triangles[i][k];
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(handles_->scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(handles_->scene);
}

RobustEmbree::~RobustEmbree() {
  rtcReleaseScene(handles_->scene);
  rtcReleaseDevice(handles_->device);
}

namespace {

gpu_shared::HtHit intersectOne(RTCScene scene, const gpu_shared::HtRay& ray) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = ht::embree::toEmbreeRayHit(ray);
  rtcIntersect1(scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {ray.tmax, gpu_shared::HT_MISS, 0.0f, 0.0f};
  return {rh.ray.tfar, rh.hit.primID, rh.hit.u, rh.hit.v};
}

}  // namespace

std::vector<gpu_shared::HtHit> RobustEmbree::traceClosest(std::span<const gpu_shared::HtRay> rays) const {
  std::vector<gpu_shared::HtHit> hits(rays.size());
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < threads; ++w) {
    pool.emplace_back([&, w] {
      for (size_t i = w; i < rays.size(); i += threads) hits[i] = intersectOne(handles_->scene, rays[i]);
    });
  }
  for (std::thread& t : pool) t.join();
  return hits;
}

}  // namespace ht::accuracy
