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

layout(constant_id = 0) const uint SHADOW_QUEUE = 1u;

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
    HtTraceResult r;
    if (TWO_LEVEL) {
      r = ht_trace_two_level_any(ray, FRAME.scene.z);
    } else {
      r = ht_trace_any(ray, FRAME.scene.z);
    }
    steps = r.steps;
    overflow = r.overflow;
    if (SHADOW_QUEUE == 1u) {
      if (r.hit.triId != HT_MISS || r.overflow) imageStore(shadowContribBuffer, int(slot), vec4(0.0f, 0.0f, 0.0f, 1.0f));
    } else {
      store_hit(i, r.hit);
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
