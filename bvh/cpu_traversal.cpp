// cpu_traversal.cpp - see cpu_traversal.h.
#include "bvh/cpu_traversal.h"

#include <algorithm>
#include <atomic>
#include <thread>

namespace ht::bvh {
namespace {

gpu_shared::BvhView viewOf(const GpuBvh& bvh) { return gpu_shared::BvhView{bvh.nodes.data(), bvh.triangles.data()}; }

template <bool kAnyHit>
HtTraceResult traceOne(const GpuBvh& bvh, const HtRay& ray, uint32_t stepLimit) {
  if (bvh.nodes.empty()) return gpu_shared::ht_trace_miss(ray);
  gpu_shared::BvhView view = viewOf(bvh);
  return kAnyHit ? gpu_shared::ht_trace_any(view, ray, stepLimit)
                 : gpu_shared::ht_trace_closest_ordered(view, ray, stepLimit);
}

// Workers take blocks of kBlock consecutive rays from a shared counter: neighbouring rays are coherent
// (cache friendly) and cheap and expensive regions of an image are spread over all threads.
constexpr size_t kBlock = 1024;

template <class TraceOne>
std::vector<HtTraceResult> traceBatch(std::span<const HtRay> rays, uint32_t threads, TraceOne traceOneRay) {
  std::vector<HtTraceResult> results(rays.size());
  const size_t blocks = (rays.size() + kBlock - 1) / kBlock;
  uint32_t workers = threads != 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
  workers = static_cast<uint32_t>(std::min<size_t>(workers, std::max<size_t>(1, blocks)));
  std::atomic<size_t> nextBlock{0};
  auto work = [&] {
    for (size_t b = nextBlock++; b < blocks; b = nextBlock++) {
      const size_t end = std::min(rays.size(), (b + 1) * kBlock);
      for (size_t i = b * kBlock; i < end; ++i) results[i] = traceOneRay(rays[i]);
    }
  };
  std::vector<std::thread> pool;
  for (uint32_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  return results;
}

}  // namespace

HtTraceResult traceClosest(const GpuBvh& bvh, const HtRay& ray, uint32_t stepLimit) {
  return traceOne<false>(bvh, ray, stepLimit);
}

HtTraceResult traceAny(const GpuBvh& bvh, const HtRay& ray, uint32_t stepLimit) {
  return traceOne<true>(bvh, ray, stepLimit);
}

std::vector<HtTraceResult> traceClosestBatch(const GpuBvh& bvh, std::span<const HtRay> rays, uint32_t stepLimit,
                                             uint32_t threads) {
  return traceBatch(rays, threads, [&](const HtRay& r) { return traceOne<false>(bvh, r, stepLimit); });
}

std::vector<HtTraceResult> traceAnyBatch(const GpuBvh& bvh, std::span<const HtRay> rays, uint32_t stepLimit,
                                         uint32_t threads) {
  return traceBatch(rays, threads, [&](const HtRay& r) { return traceOne<true>(bvh, r, stepLimit); });
}

HtTraceResult traceClosestTwoLevel(const TwoLevelBvh& bvh, const HtRay& ray, uint32_t stepLimit) {
  const gpu_shared::TwoLevelView view = bvh.view();
  return gpu_shared::ht_trace_two_level_ordered(view, view.blas, ray, stepLimit);
}

std::vector<HtTraceResult> traceClosestTwoLevelBatch(const TwoLevelBvh& bvh, std::span<const HtRay> rays,
                                                     uint32_t stepLimit, uint32_t threads) {
  return traceBatch(rays, threads, [&](const HtRay& r) { return traceClosestTwoLevel(bvh, r, stepLimit); });
}

}  // namespace ht::bvh
