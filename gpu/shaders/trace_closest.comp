#version 460
#extension GL_GOOGLE_include_directive : require
// trace_closest: one closest-hit traversal per invocation (one ray per invocation per dispatch: lavapipe ends
// every loop of an invocation after 65,535 iterations in total, docs/TOOLCHAIN.md §0). Rays past the step limit are
// counted in overflowCount, which the host turns into an error.
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu/shaders/bvh_access.glsl"
#include "bvh/bvh_traversal.h"

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool inQueue = i < COUNTERS.queueCount[pc.queue];
  uint steps = 0u;
  bool overflow = false;
  if (inQueue) {
    HtTraceResult r = ht_trace_closest(load_ray(pc.queue, i), FRAME.scene.z);
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
