// embree_tracer.cpp - see embree_tracer.h.
#include "bench/embree_tracer.h"

#include "bench/embree_handles.h"
#include "bench/embree_ray.h"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <chrono>
#include <limits>
#include <string>

#include "bench/parallel_tiles.h"
#include "common/error.h"

namespace ht::bench {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::uint32_t kTileSize = 16;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void throwOnDeviceError(RTCDevice device, const char* step) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) {
    throw Error(std::string("Embree: ") + step + " failed with RTCError " + std::to_string(int(error)));
  }
}

// Embree's recommended per-thread setting ("for performance reasons", rtcore API docs): flush denormals.
void setEmbreeFloatMode() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace

EmbreeTracer::EmbreeTracer(const Scene& scene) : handles_(std::make_unique<Handles>()) {
  handles_->device = rtcNewDevice(nullptr);
  if (!handles_->device)
    throw Error("Embree: rtcNewDevice failed (RTCError " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  const auto start = Clock::now();
  handles_->scene = rtcNewScene(handles_->device);
  RTCGeometry geometry = rtcNewGeometry(handles_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), scene.positions.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), scene.triangles.size()));
  throwOnDeviceError(handles_->device, "buffer allocation");
  for (std::size_t i = 0; i < scene.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) vertices[3 * i + k] = scene.positions[i][k];
  }
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) indices[3 * i + k] = scene.triangles[i][k];
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(handles_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(handles_->scene);
  throwOnDeviceError(handles_->device, "scene build");
  buildMs_ = msSince(start);
}

EmbreeTracer::~EmbreeTracer() = default;

const char* EmbreeTracer::version() { return RTC_VERSION_STRING; }

std::vector<gpu_shared::HtHit> EmbreeTracer::traceClosest(std::span<const gpu_shared::HtRay> rays, std::uint32_t width,
                                                          unsigned threads, double* wallMs) const {
  std::vector<gpu_shared::HtHit> hits(rays.size());
  const std::uint32_t height = std::uint32_t(rays.size() / width);
  RTCScene scene = handles_->scene;
  const auto start = Clock::now();
  forEachTileParallel(width, height, kTileSize, threads, [&](const Tile& tile) {
    setEmbreeFloatMode();
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::uint32_t y = tile.y0; y < tile.y1; ++y) {
      for (std::uint32_t x = tile.x0; x < tile.x1; ++x) {
        const std::size_t i = std::size_t(y) * width + x;
        RTCRayHit rayHit = ht::embree::toEmbreeRayHit(rays[i]);
        rtcIntersect1(scene, &context, &rayHit);
        const bool hit = rayHit.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        hits[i] = {rayHit.ray.tfar, hit ? rayHit.hit.primID : gpu_shared::HT_MISS, rayHit.hit.u, rayHit.hit.v};
      }
    }
  });
  *wallMs = msSince(start);
  return hits;
}

std::vector<std::uint32_t> EmbreeTracer::traceOccluded(std::span<const gpu_shared::HtRay> rays, std::uint32_t width,
                                                       unsigned threads, double* wallMs) const {
  std::vector<std::uint32_t> occluded(rays.size());
  const std::uint32_t height = std::uint32_t(rays.size() / width);
  RTCScene scene = handles_->scene;
  const auto start = Clock::now();
  forEachTileParallel(width, height, kTileSize, threads, [&](const Tile& tile) {
    setEmbreeFloatMode();
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::uint32_t y = tile.y0; y < tile.y1; ++y) {
      for (std::uint32_t x = tile.x0; x < tile.x1; ++x) {
        const std::size_t i = std::size_t(y) * width + x;
        RTCRay ray = ht::embree::toEmbreeRay(rays[i]);
        rtcOccluded1(scene, &context, &ray);
        occluded[i] = ray.tfar == -std::numeric_limits<float>::infinity() ? 1u : 0u;
      }
    }
  });
  *wallMs = msSince(start);
  return occluded;
}

}  // namespace ht::bench
