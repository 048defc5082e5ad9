// embree_packets.cpp - EmbreeTracer's flat-batch queries: rtcIntersect1/rtcOccluded1 per ray or
// rtcIntersect8/rtcOccluded8 on packets of 8 consecutive rays (the tail packet masks its unused lanes).
#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "bench/embree_handles.h"
#include "bench/embree_ray.h"
#include "bench/embree_tracer.h"
#include "bench/parallel_tiles.h"

namespace ht::bench {
namespace {

using gpu_shared::HtHit;
using gpu_shared::HtRay;
using Clock = std::chrono::steady_clock;
constexpr float kOccludedTfar = -std::numeric_limits<float>::infinity();

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void setEmbreeFloatMode() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

// Lane k of an 8-wide SoA ray from an HtRay (mask all bits, as toEmbreeRay).
void setLane(RTCRay8& r, int k, const HtRay& ray) {
  r.org_x[k] = ray.origin.x;
  r.org_y[k] = ray.origin.y;
  r.org_z[k] = ray.origin.z;
  r.tnear[k] = ray.tmin;
  r.dir_x[k] = ray.dir.x;
  r.dir_y[k] = ray.dir.y;
  r.dir_z[k] = ray.dir.z;
  r.tfar[k] = ray.tmax;
  r.time[k] = 0.0f;
  r.mask[k] = 0xFFFFFFFFu;
  r.id[k] = 0;
  r.flags[k] = 0;
}

void closestSingle(RTCScene scene, std::span<const HtRay> rays, std::size_t begin, std::size_t end,
                   std::vector<HtHit>& hits) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (std::size_t i = begin; i < end; ++i) {
    RTCRayHit rayHit = ht::embree::toEmbreeRayHit(rays[i]);
    rtcIntersect1(scene, &context, &rayHit);
    const bool hit = rayHit.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    hits[i] = {rayHit.ray.tfar, hit ? rayHit.hit.primID : gpu_shared::HT_MISS, rayHit.hit.u, rayHit.hit.v};
  }
}

void closestPacket8(RTCScene scene, std::span<const HtRay> rays, std::size_t begin, std::size_t end,
                    std::vector<HtHit>& hits) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(32) int valid[8];
  alignas(32) RTCRayHit8 packet;
  for (std::size_t first = begin; first < end; first += 8) {
    const int lanes = int(std::min<std::size_t>(8, end - first));
    for (int k = 0; k < 8; ++k) {
      valid[k] = k < lanes ? -1 : 0;
      setLane(packet.ray, k, rays[first + std::min(k, lanes - 1)]);
      packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, scene, &context, &packet);
    for (int k = 0; k < lanes; ++k) {
      const bool hit = packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
      hits[first + k] = {packet.ray.tfar[k], hit ? packet.hit.primID[k] : gpu_shared::HT_MISS, packet.hit.u[k],
                         packet.hit.v[k]};
    }
  }
}

void occludedSingle(RTCScene scene, std::span<const HtRay> rays, std::size_t begin, std::size_t end,
                    std::vector<std::uint32_t>& occluded) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (std::size_t i = begin; i < end; ++i) {
    RTCRay ray = ht::embree::toEmbreeRay(rays[i]);
    rtcOccluded1(scene, &context, &ray);
    occluded[i] = ray.tfar == kOccludedTfar ? 1u : 0u;
  }
}

void occludedPacket8(RTCScene scene, std::span<const HtRay> rays, std::size_t begin, std::size_t end,
                     std::vector<std::uint32_t>& occluded) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(32) int valid[8];
  alignas(32) RTCRay8 packet;
  for (std::size_t first = begin; first < end; first += 8) {
    const int lanes = int(std::min<std::size_t>(8, end - first));
    for (int k = 0; k < 8; ++k) {
      valid[k] = k < lanes ? -1 : 0;
      setLane(packet, k, rays[first + std::min(k, lanes - 1)]);
    }
    rtcOccluded8(valid, scene, &context, &packet);
    for (int k = 0; k < lanes; ++k) occluded[first + k] = packet.tfar[k] == kOccludedTfar ? 1u : 0u;
  }
}

}  // namespace

std::vector<HtHit> EmbreeTracer::traceClosestFlat(std::span<const HtRay> rays, Api api, unsigned threads,
                                                  double* wallMs) const {
  std::vector<HtHit> hits(rays.size());
  RTCScene scene = handles_->scene;
  const auto start = Clock::now();
  forEachChunkParallel(rays.size(), kFlatChunk, threads, [&](std::size_t begin, std::size_t end) {
    setEmbreeFloatMode();
    if (api == Api::Packet8)
      closestPacket8(scene, rays, begin, end, hits);
    else
      closestSingle(scene, rays, begin, end, hits);
  });
  *wallMs = msSince(start);
  return hits;
}

std::vector<std::uint32_t> EmbreeTracer::traceOccludedFlat(std::span<const HtRay> rays, Api api, unsigned threads,
                                                           double* wallMs) const {
  std::vector<std::uint32_t> occluded(rays.size());
  RTCScene scene = handles_->scene;
  const auto start = Clock::now();
  forEachChunkParallel(rays.size(), kFlatChunk, threads, [&](std::size_t begin, std::size_t end) {
    setEmbreeFloatMode();
    if (api == Api::Packet8)
      occludedPacket8(scene, rays, begin, end, occluded);
    else
      occludedSingle(scene, rays, begin, end, occluded);
  });
  *wallMs = msSince(start);
  return occluded;
}

}  // namespace ht::bench
