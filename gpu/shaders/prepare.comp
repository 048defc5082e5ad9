#version 460
#extension GL_GOOGLE_include_directive : require
// prepare: a single invocation that maintains queue counters between passes, so no pass needs a host
// round trip and an empty queue becomes an indirect dispatch of zero workgroups (docs/BVH.md §7).
//   MODE 0 (after shade):  indirect arguments for the shadow queue and the next ray queue.
//   MODE 1 (end of depth): the consumed queue and the shadow queue are emptied for the next depth.
#include "gpu/shaders/common.glsl"

layout(constant_id = 0) const uint MODE = 0u;

uvec4 groups_for(uint count) { return uvec4((count + HT_WORKGROUP_SIZE - 1u) / HT_WORKGROUP_SIZE, 1u, 1u, 0u); }

void main() {
  if (gl_GlobalInvocationID.x != 0u) return;
  uint next = 1u - pc.queue;
  if (MODE == 0u) {
    COUNTERS.dispatch[2] = groups_for(COUNTERS.shadowCount);
    COUNTERS.dispatch[next] = groups_for(COUNTERS.queueCount[next]);
  } else {
    COUNTERS.queueCount[pc.queue] = 0u;
    COUNTERS.shadowCount = 0u;
  }
}
