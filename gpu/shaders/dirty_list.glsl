// dirty_list.glsl - how the marking passes (mark_dirty.comp, mark_accumulated.comp) list a dirty target
// (gpu/frame_reuse.h, docs/REUSE.md §4). Included after common.glsl with GL_KHR_shader_subgroup_ballot and
// GL_KHR_shader_subgroup_arithmetic enabled.

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

// Appends values[0, n) to the list of append_where, with one subgroup scan and one atomic per subgroup for all of
// them. Called by every invocation.
void append_values(uint n, uint values[HT_MARK_TARGETS_PER_INVOCATION], uint countWord, uint first) {
  uint total = subgroupAdd(n);
  if (total == 0u) return;  // uniform: the whole subgroup leaves
  uint at = subgroupExclusiveAdd(n);
  uint base = 0u;
  if (subgroupElect()) base = atomicAdd(UintRef(FRAME.refine).v[countWord], total);
  at += subgroupBroadcastFirst(base);
  for (uint k = 0u; k < n; ++k) UintRef(FRAME.refine).v[first + at + k] = values[k];
}

// Appends target `firstTarget + k` for every bit k of `bits` (k < HT_MARK_TARGETS_PER_INVOCATION), as append_values.
void append_bits(uint bits, uint countWord, uint first, uint firstTarget) {
  uint values[HT_MARK_TARGETS_PER_INVOCATION];
  uint n = 0u;
  for (; bits != 0u; bits &= bits - 1u) values[n++] = firstTarget + uint(findLSB(bits));
  append_values(n, values, countWord, first);
}

// What starts over for a dirty target: its mask words 0-1, cleared for the re-trace to record again; in an
// accumulation (`resetAccumulation`) words 2-3, its sums and what bounds its primary segments too. A single frame's
// words 2-3 (the cells of its cached primary segments and their shadow rays) only pick the candidates of the exact
// tests, which read the cached rays and hits themselves, so a superset of the current segments' cells is as safe: the
// re-trace adds the cells of the paths whose primary hit changed and skips those that kept it (record_segments.comp).
void clear_dirty_target(uint target, bool resetAccumulation) {
  uint words = resetAccumulation ? 4u : 2u;
  for (uint w = 0u; w < words; ++w) UintRef(FRAME.segmentMasks).v[4u * target + w] = 0u;
  if (resetAccumulation) {
    store_accum_target(frame_global_target(target), AccumTarget(vec3(0.0f), 0u, vec3(0.0f), 0u));
    UintRef(FRAME.segmentMasks).v[accum_reach_word(target)] = 0u;
    UintRef(FRAME.segmentMasks).v[accum_near_hit_word(target)] = 0u;
    UintRef(FRAME.segmentMasks).v[accum_far_hit_word(target)] = 0u;
  }
}

// A dirty target: listed, and what starts over cleared. Called by every invocation.
void mark_dirty(bool dirty, uint target, bool resetAccumulation) {
  append_where(dirty, 2u, FRAME.refineInfo.y, target);
  if (dirty) clear_dirty_target(target, resetAccumulation);
}
