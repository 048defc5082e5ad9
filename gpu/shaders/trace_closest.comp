#version 460
#extension GL_GOOGLE_include_directive : require
// trace_closest: one closest-hit traversal per invocation (one ray per invocation per dispatch: lavapipe ends
// every loop of an invocation after 65,535 iterations in total, docs/TOOLCHAIN.md §0). Rays past the step limit are
// counted in overflowCount, which the host turns into an error. The closest hit is the order-free one, the least
// (t, triangle id) (bvh/ordered_traversal.h, docs/BVH.md §9.3): the same for every tree over the same triangles,
// so a rebuilt, refitted or two-level BVH gives the same frame bits. Every loop iteration of the traversal counts a
// step, so a loop lavapipe cut short has used more than HT_TRAVERSAL_STEP_LIMIT steps and sets overflow.
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu/shaders/bvh_access.glsl"
#include "bvh/ordered_traversal.h"
#include "gpu/segment_cells.h"

// The primary rays of a partial re-render with the primary hits cached (ReusePlan::primaryCached; docs/REUSE.md §4):
// a ray whose cached segment, up to its cached hit, does not meet the padded moved bounds (FRAME.refine words 4-6,
// 8-10) has that same hit in the edited scene -- every triangle of the moved node lies inside those bounds, every
// other triangle is unchanged, and the closest hit is the order-free one -- so it takes the cached hit and is not
// traced. Most re-traced targets are re-traced for a shadow or a reflection, not for their primary ray.
layout(constant_id = 0) const bool REUSE_PRIMARY = false;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer HitCacheRef { uvec4 h[]; };

// The cached primary hit of queue-0 entry i (= path i of the batch), if the moved node cannot have changed it.
bool cached_primary_hit(uint i, HtRay ray, out HtHit hit) {
  uint spp = FRAME.dims.z;
  uint entry = (pc.batchFirst + i) / spp;
  uint target = UintRef(FRAME.refine).v[FRAME.refineInfo.y + entry];
  uvec4 h = HitCacheRef(FRAME.primaryHits).h[target * spp + (pc.batchFirst + i) % spp];
  hit = HtHit(uintBitsToFloat(h.x), h.y, uintBitsToFloat(h.z), uintBitsToFloat(h.w));
  uint w = 4u;
  vec3 lo = uintBitsToFloat(uvec3(UintRef(FRAME.refine).v[w], UintRef(FRAME.refine).v[w + 1u], UintRef(FRAME.refine).v[w + 2u]));
  w = 8u;
  vec3 hi = uintBitsToFloat(uvec3(UintRef(FRAME.refine).v[w], UintRef(FRAME.refine).v[w + 1u], UintRef(FRAME.refine).v[w + 2u]));
  return !ht_segment_meets_box(ray.origin, ray.dir, ray.tmin, hit.triId != HT_MISS ? hit.t : ray.tmax, lo, hi);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool inQueue = i < COUNTERS.queueCount[pc.queue];
  uint steps = 0u;
  bool overflow = false;
  HtRay ray;
  HtHit cached;
  if (inQueue) ray = load_ray(pc.queue, i);
  if (REUSE_PRIMARY && inQueue && cached_primary_hit(i, ray, cached)) {
    store_hit(i, cached);
    inQueue = false;  // not traced
  }
  if (inQueue) {
    HtTraceResult r;
    if (TWO_LEVEL) {
      r = ht_trace_two_level_ordered(ray, FRAME.scene.z);
    } else {
      r = ht_trace_closest_ordered(ray, FRAME.scene.z);
    }
    store_hit(i, r.hit);
    steps = r.steps;
    overflow = r.overflow;
  }
  // One atomic per subgroup instead of one per ray.
  uint maxSteps = subgroupMax(steps);
  uint overflows = subgroupAdd(overflow ? 1u : 0u);
  uint traced = subgroupAdd(inQueue ? 1u : 0u);
  if (subgroupElect()) {
    if (traced > 0u) atomicAdd(COUNTERS.raysTraced, traced);
    if (overflows > 0u) atomicAdd(COUNTERS.overflowCount, overflows);
    if (maxSteps > 0u) atomicMax(COUNTERS.maxSteps, maxSteps);
  }
}
