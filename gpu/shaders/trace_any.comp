#version 460
#extension GL_GOOGLE_include_directive : require
// trace_any: early-exit occlusion test, one ray per invocation.
//   SHADOW_QUEUE = 1: entry i of the shadow queue names a slot; an occluded slot's contribution is zeroed.
//   SHADOW_QUEUE = 0: plain batch (Renderer::traceOccluded): ray i of queue 0, result in hits[i].triId.
// Occlusion is the same on the flattened and the two-level BVH (the same triangle test with the ray's tmax). A shadow
// ray that leaves a convex part on its outside (the queue entry's .y, shade.comp) skips that part: its instance on a
// two-level BVH, its tagged triangles on a flattened one (docs/BVH.md §9.6).
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu/shaders/bvh_access.glsl"
#include "bvh/ordered_traversal.h"
#include "gpu/segment_cells.h"

layout(constant_id = 0) const uint SHADOW_QUEUE = 1u;
// Frame reuse (docs/REUSE.md §3-4): records each traced ray's occlusion in the occlusion cache (HT_SHADOW_CACHE_*,
// gpu/wavefront_types.h), whose word shade.comp (OCCLUSION) wrote for this depth: RECORD for a frame's own paths,
// RECORD_LISTED for the listed targets of a partial re-render. Shade queued only the rays whose recorded occlusion
// does not hold. In a partial re-render (RECORD_LISTED), a queue entry marked HT_SHADOW_MOVED_ONLY (the recorded ray,
// unoccluded before the move) walks the moved instances alone (ht_trace_two_level_any_after_moves).
layout(constant_id = 1) const uint SHADOW_CACHE = HT_SHADOW_CACHE_OFF;

#include "gpu/shaders/reuse_cache.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint count = SHADOW_QUEUE == 1u ? COUNTERS.shadowCount : COUNTERS.queueCount[0];
  bool inQueue = i < count;
  uint steps = 0u;
  bool overflow = false;
  if (inQueue) {
    uvec2 queued = SHADOW_QUEUE == 1u ? imageLoad(shadowQueueBuffer, int(i)).xy : uvec2(i, 0u);
    uint entry = queued.x;
    uint leaves = queued.y;  // the convex part the ray leaves on its outside (shade.comp), 0 for none
    // (only a partial re-render's shade sets HT_SHADOW_MOVED_ONLY, and only where the moved instances are known)
    bool movedOnly = SHADOW_CACHE == HT_SHADOW_CACHE_RECORD_LISTED && (entry & HT_SHADOW_MOVED_ONLY) != 0u;
    uint slot = SHADOW_CACHE == HT_SHADOW_CACHE_RECORD_LISTED ? entry & ~HT_SHADOW_MOVED_ONLY : entry;
    // (if/else, not ?: -- glslang 12 emits an invalid OpStore for a ternary over buffer-reference structs)
    HtRay ray;
    if (SHADOW_QUEUE == 1u) {
      ray = load_shadow_ray(slot);
    } else {
      ray = load_ray(0u, i);
    }
    HtTraceResult r;
    if (TWO_LEVEL && SHADOW_CACHE == HT_SHADOW_CACHE_RECORD_LISTED) {
      // One walk for every lane (lavapipe runs both sides of a divergent branch): whole, or the moved instances alone.
      r = ht_trace_two_level_any_after_moves(ray, FRAME.scene.z, movedOnly, FRAME.movedInstanceIds, leaves);
    } else if (TWO_LEVEL) {
      r = ht_trace_two_level_any_leaving(ray, FRAME.scene.z, leaves);
    } else {
      r = ht_trace_any_leaving(ray, FRAME.scene.z, leaves);
    }
    steps = r.steps;
    overflow = r.overflow;
    bool occluded = r.hit.triId != HT_MISS || r.overflow;
    if (SHADOW_QUEUE == 1u) {
      if (occluded) imageStore(shadowContribBuffer, int(slot), vec4(0.0f, 0.0f, 0.0f, 1.0f));
    } else {
      store_hit(i, r.hit);
    }
    if (SHADOW_CACHE != HT_SHADOW_CACHE_OFF) {
      uint lightCount = FRAME.scene.x, l = slot % lightCount;
      uint word = occlusion_word_index(slot / lightCount, SHADOW_CACHE == HT_SHADOW_CACHE_RECORD_LISTED);
      uint bits = (1u << (HT_OCCLUSION_TRACED_SHIFT + l)) | (occluded ? 1u << l : 0u);
      atomicOr(UintRef(FRAME.shadowOcclusion).v[word], bits);
    }
  }
  uint maxSteps = subgroupMax(steps);
  uint overflows = subgroupAdd(overflow ? 1u : 0u);
  uint traced = subgroupAdd(inQueue ? 1u : 0u);
  if (subgroupElect()) {
    if (traced > 0u) atomicAdd(COUNTERS.raysTraced, traced);
    if (overflows > 0u) atomicAdd(COUNTERS.overflowCount, overflows);
    if (maxSteps > 0u) atomicMax(COUNTERS.maxSteps, maxSteps);
  }
}
