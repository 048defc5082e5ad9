// dirty_list.glsl - how the marking passes (mark_dirty.comp, mark_accumulated.comp) list a dirty target
// (gpu/frame_reuse.h, docs/REUSE.md §4). Included after common.glsl with GL_KHR_shader_subgroup_ballot enabled.

// Appends `value` where `want`, to the list whose count is header word `countWord` and whose entries start at word
// `first` (one atomic per subgroup). Called by every invocation (subgroup operations).
void append_where(bool want, uint countWord, uint first, uint value) {
  uvec4 ballot = subgroupBallot(want);
  uint total = subgroupBallotBitCount(ballot);
  uint base = 0u;
  if (subgroupElect() && total > 0u) base = atomicAdd(UintRef(FRAME.refine).v[countWord], total);
  base = subgroupBroadcastFirst(base);
  if (want) UintRef(FRAME.refine).v[first + base + subgroupBallotExclusiveBitCount(ballot)] = value;
}

// A dirty target: listed, its mask cleared for the re-trace to record again; in an accumulation
// (`resetAccumulation`) its sums and what bounds its primary segments start over too. Called by every invocation.
void mark_dirty(bool dirty, uint target, bool resetAccumulation) {
  append_where(dirty, 2u, FRAME.refineInfo.y, target);
  if (dirty) {
    for (uint w = 0u; w < 4u; ++w) UintRef(FRAME.segmentMasks).v[4u * target + w] = 0u;
    if (resetAccumulation) {
      AccumRef(FRAME.accumTargets).t[frame_global_target(target)] = AccumTarget(vec3(0.0f), 0u, vec3(0.0f), 0u);
      UintRef(FRAME.segmentMasks).v[accum_reach_word(target)] = 0u;
      UintRef(FRAME.segmentMasks).v[accum_near_hit_word(target)] = 0u;
      UintRef(FRAME.segmentMasks).v[accum_far_hit_word(target)] = 0u;
    }
  }
}
