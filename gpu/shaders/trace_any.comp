#version 460
#extension GL_GOOGLE_include_directive : require
// trace_any: early-exit occlusion test, one ray per invocation.
//   SHADOW_QUEUE = 1: entry i of the shadow queue names a slot; an occluded slot's contribution is zeroed.
//   SHADOW_QUEUE = 0: plain batch (Renderer::traceOccluded): ray i of queue 0, result in hits[i].triId.
// Occlusion is the same on the flattened and the two-level BVH (the same triangle test with the ray's tmax).
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu/shaders/bvh_access.glsl"
#include "bvh/ordered_traversal.h"
#include "gpu/segment_cells.h"

layout(constant_id = 0) const uint SHADOW_QUEUE = 1u;
// Frame reuse (docs/REUSE.md §4), depth-0 shadow rays only: 1 records each ray's occlusion in FRAME.shadowOcclusion
// (a frame that caches its primary hits); 2, in a partial re-render, takes the recorded occlusion of a ray whose path
// kept its cached primary hit (the same surface point and lights, so the same ray as recorded) and whose segment
// avoids the padded moved bounds (FRAME.refine words 4-6, 8-10: no moved triangle can meet it), and records the
// others.
const uint SHADOW_CACHE_OFF = 0u, SHADOW_CACHE_RECORD = 1u, SHADOW_CACHE_REUSE = 2u;
layout(constant_id = 1) const uint SHADOW_CACHE = SHADOW_CACHE_OFF;

#include "gpu/shaders/reuse_cache.glsl"

// The frame-wide path of shadow slot `slot` (slot = batch path * lights + light).
uint slot_frame_path(uint slot) {
  uint path = slot / FRAME.scene.x;
  return SHADOW_CACHE == SHADOW_CACHE_REUSE ? listed_frame_path(path) : pc.batchFirst + path;
}

// Is the recorded occlusion of this depth-0 shadow ray of frame path `path` still its occlusion?
bool recorded_occlusion_holds(uint path, HtRay shadow) {
  return !cached_primary_meets_moved(path) &&
         !ht_segment_meets_box(shadow.origin, shadow.dir, shadow.tmin, shadow.tmax, moved_lo(), moved_hi());
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint count = SHADOW_QUEUE == 1u ? COUNTERS.shadowCount : COUNTERS.queueCount[0];
  bool inQueue = i < count;
  uint steps = 0u;
  bool overflow = false;
  if (inQueue) {
    uint slot = SHADOW_QUEUE == 1u ? imageLoad(shadowQueueBuffer, int(i)).x : i;
    // (if/else, not ?: -- glslang 12 emits an invalid OpStore for a ternary over buffer-reference structs)
    HtRay ray;
    if (SHADOW_QUEUE == 1u) {
      ray = load_shadow_ray(slot);
    } else {
      ray = load_ray(0u, i);
    }
    uint cachePath = 0u, cacheBit = 0u;
    bool recorded = false;
    if (SHADOW_CACHE != SHADOW_CACHE_OFF) {
      cachePath = slot_frame_path(slot);
      cacheBit = 1u << (slot % FRAME.scene.x);
      if (SHADOW_CACHE == SHADOW_CACHE_REUSE) {
        load_moved_view();
        recorded = recorded_occlusion_holds(cachePath, ray);
      }
    }
    if (recorded) {
      inQueue = false;  // not traced
      if ((UintRef(FRAME.shadowOcclusion).v[cachePath] & cacheBit) != 0u) {
        imageStore(shadowContribBuffer, int(slot), vec4(0.0f, 0.0f, 0.0f, 1.0f));
      }
    } else {
      HtTraceResult r;
      if (TWO_LEVEL) {
        r = ht_trace_two_level_any(ray, FRAME.scene.z);
      } else {
        r = ht_trace_any(ray, FRAME.scene.z);
      }
      steps = r.steps;
      overflow = r.overflow;
      bool occluded = r.hit.triId != HT_MISS || r.overflow;
      if (SHADOW_QUEUE == 1u) {
        if (occluded) imageStore(shadowContribBuffer, int(slot), vec4(0.0f, 0.0f, 0.0f, 1.0f));
      } else {
        store_hit(i, r.hit);
      }
      if (SHADOW_CACHE != SHADOW_CACHE_OFF) {
        if (occluded) {
          atomicOr(UintRef(FRAME.shadowOcclusion).v[cachePath], cacheBit);
        } else {
          atomicAnd(UintRef(FRAME.shadowOcclusion).v[cachePath], ~cacheBit);
        }
      }
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
