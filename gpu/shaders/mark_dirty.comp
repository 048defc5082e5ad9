#version 460
#extension GL_GOOGLE_include_directive : require
// mark_dirty: the marking pass of a partial re-render (gpu/frame_reuse.h, docs/REUSE.md §4), one invocation per
// target of the frame: a target whose segment cells meet the moved bounds' cells (FRAME.refine words 0-1) is
// appended to the dirty list (count in word 2, entries from word FRAME.refineInfo.y) and its mask cleared for the
// re-trace to record again. With the primary rays and hits cached (FRAME.primaryHits != 0), a target is also dirty
// when its primary segments' cells (mask words 2-3) meet those cells and a primary segment of one of its samples
// meets the padded moved bounds (FRAME.refine words 4-6 and 8-10, float
// bits). List order varies with scheduling; a target's samples do not depend on it.
// CPU reference: gpu::markDirtyTargets (gpu/frame_reuse.h).
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_ballot : require
#include "gpu/segment_cells.h"

// In a progressive accumulation after node moves (accumulation_pass.cpp resetMovedTargets): a dirty target's sums
// start over too (sum, n, half sum, half count = 0); the others keep theirs.
layout(constant_id = 0) const bool RESET_ACCUMULATION = false;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RayCacheRef { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer HitCacheRef { uvec4 h[]; };

vec3 header_vec3(uint first) {
  return uintBitsToFloat(uvec3(UintRef(FRAME.refine).v[first], UintRef(FRAME.refine).v[first + 1u],
                               UintRef(FRAME.refine).v[first + 2u]));
}

// Does a primary segment of one of the target's samples meet the moved bounds?
bool primary_meets_moved(uint target) {
  vec3 lo = header_vec3(4u), hi = header_vec3(8u);
  uint spp = FRAME.dims.z;
  for (uint s = 0u; s < spp; ++s) {
    uint path = target * spp + s;
    vec4 a = RayCacheRef(FRAME.primaryRays).v[2u * path], b = RayCacheRef(FRAME.primaryRays).v[2u * path + 1u];
    uvec4 hit = HitCacheRef(FRAME.primaryHits).h[path];
    float tEnd = hit.y != HT_MISS ? uintBitsToFloat(hit.x) : b.w;
    if (ht_segment_meets_box(a.xyz, b.xyz, a.w, tEnd, lo, hi)) return true;
  }
  return false;
}

void main() {
  uint target = pc.batchFirst + gl_GlobalInvocationID.x;  // dispatched in slices of targets; batchCount: all
  bool dirty = false;
  if (target < pc.batchCount) {
    uvec4 mask = uvec4(UintRef(FRAME.segmentMasks).v[4u * target], UintRef(FRAME.segmentMasks).v[4u * target + 1u],
                       UintRef(FRAME.segmentMasks).v[4u * target + 2u], UintRef(FRAME.segmentMasks).v[4u * target + 3u]);
    uvec2 moved = uvec2(UintRef(FRAME.refine).v[0], UintRef(FRAME.refine).v[1]);
    dirty = ((mask.x & moved.x) | (mask.y & moved.y)) != 0u;
    bool primaryNear = ((mask.z & moved.x) | (mask.w & moved.y)) != 0u;
    if (!dirty && primaryNear) dirty = primary_meets_moved(target);
  }
  uvec4 ballot = subgroupBallot(dirty);
  uint total = subgroupBallotBitCount(ballot);
  uint base = 0u;
  if (subgroupElect() && total > 0u) base = atomicAdd(UintRef(FRAME.refine).v[2], total);
  base = subgroupBroadcastFirst(base);
  if (dirty) {
    UintRef(FRAME.refine).v[FRAME.refineInfo.y + base + subgroupBallotExclusiveBitCount(ballot)] = target;
    for (uint w = 0u; w < 4u; ++w) UintRef(FRAME.segmentMasks).v[4u * target + w] = 0u;
    if (RESET_ACCUMULATION) AccumRef(FRAME.accumTargets).t[frame_global_target(target)] = AccumTarget(vec3(0.0f), 0u, vec3(0.0f), 0u);
  }
}
