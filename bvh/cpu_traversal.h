// cpu_traversal.h - host execution of the shared traversal code (bvh_traversal.h) over a GpuBvh: the CPU
// reference of the GPU kernel (same source, same arithmetic: C++ is built with -ffp-contract=off).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "bvh/bvh_traversal.h"
#include "bvh/gpu_layout.h"
#include "bvh/two_level_bvh.h"

namespace ht::bvh {

using gpu_shared::HtHit;
using gpu_shared::HtRay;
using gpu_shared::HtTraceResult;

// Closest hit, order-free (ordered_traversal.h, docs/BVH.md §9.3): the least (t, triangle id), identical for every
// tree over the same triangles; the CPU reference of gpu/shaders/trace_closest.comp. A GpuBvh without nodes
// (default-constructed) returns a miss.
HtTraceResult traceClosest(const GpuBvh& bvh, const HtRay& ray,
                           uint32_t stepLimit = gpu_shared::HT_TRAVERSAL_STEP_LIMIT);
// Any hit (occlusion): hit.triId != HT_MISS when something lies in [tmin, tmax].
HtTraceResult traceAny(const GpuBvh& bvh, const HtRay& ray, uint32_t stepLimit = gpu_shared::HT_TRAVERSAL_STEP_LIMIT);

// Batch versions: result i belongs to ray i; rays are split over `threads` std::threads (0 = all cores).
std::vector<HtTraceResult> traceClosestBatch(const GpuBvh& bvh, std::span<const HtRay> rays,
                                             uint32_t stepLimit = gpu_shared::HT_TRAVERSAL_STEP_LIMIT,
                                             uint32_t threads = 0);
std::vector<HtTraceResult> traceAnyBatch(const GpuBvh& bvh, std::span<const HtRay> rays,
                                         uint32_t stepLimit = gpu_shared::HT_TRAVERSAL_STEP_LIMIT,
                                         uint32_t threads = 0);

// Closest hit through a two-level BVH: equals traceClosest over the flattened BVH of the same soup bit for bit.
HtTraceResult traceClosestTwoLevel(const TwoLevelBvh& bvh, const HtRay& ray,
                                   uint32_t stepLimit = gpu_shared::HT_TRAVERSAL_STEP_LIMIT);
std::vector<HtTraceResult> traceClosestTwoLevelBatch(const TwoLevelBvh& bvh, std::span<const HtRay> rays,
                                                     uint32_t stepLimit = gpu_shared::HT_TRAVERSAL_STEP_LIMIT,
                                                     uint32_t threads = 0);

}  // namespace ht::bvh
