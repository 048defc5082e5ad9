#version 460
#extension GL_GOOGLE_include_directive : require
// mark_dirty: the marking pass of a partial re-render (gpu/frame_reuse.h, docs/REUSE.md §4), one invocation per
// target of the frame: a target whose segment cells meet the moved bounds' cells (FRAME.refine words 0-1) is
// appended to the dirty list (count in word 2, entries from word FRAME.refineInfo.y) and its mask cleared for the
// re-trace to record again. List order varies with scheduling; a target's samples do not depend on it.
// CPU reference: gpu::markDirtyTargets (gpu/frame_reuse.h).
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_ballot : require

void main() {
  uint target = pc.batchFirst + gl_GlobalInvocationID.x;  // dispatched in slices of targets; batchCount: all
  bool dirty = false;
  if (target < pc.batchCount) {
    uvec2 mask = uvec2(UintRef(FRAME.segmentMasks).v[2u * target], UintRef(FRAME.segmentMasks).v[2u * target + 1u]);
    uvec2 moved = uvec2(UintRef(FRAME.refine).v[0], UintRef(FRAME.refine).v[1]);
    dirty = ((mask.x & moved.x) | (mask.y & moved.y)) != 0u;
  }
  uvec4 ballot = subgroupBallot(dirty);
  uint total = subgroupBallotBitCount(ballot);
  uint base = 0u;
  if (subgroupElect() && total > 0u) base = atomicAdd(UintRef(FRAME.refine).v[2], total);
  base = subgroupBroadcastFirst(base);
  if (dirty) {
    UintRef(FRAME.refine).v[FRAME.refineInfo.y + base + subgroupBallotExclusiveBitCount(ballot)] = target;
    UintRef(FRAME.segmentMasks).v[2u * target] = 0u;
    UintRef(FRAME.segmentMasks).v[2u * target + 1u] = 0u;
  }
}
