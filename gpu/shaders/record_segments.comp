#version 460
#extension GL_GOOGLE_include_directive : require
// record_segments: for frames that keep reuse state (gpu/frame_reuse.h, docs/REUSE.md §4), one invocation per entry
// of the current ray queue, after this depth's closest-hit trace and shadow trace and before gather_direct clears
// the shadow slots: ORs the world-grid cells of the entry's segment (to its hit; a miss to infinity) and of every
// shadow ray its path emitted at this depth (to the light) into the mask of the path's target (gpu/segment_cells.h).
// Masks are 4 words per target: words 0-1 the cells of every segment but the cached primary ones and their shadow
// rays; with the primary hits cached (FRAME.primaryHits != 0) the cells of the primary segments and of the shadow rays
// from their hits go to words 2-3 (mark_dirty.comp then tests those segments exactly where those cells meet the moved
// bounds), and a partial re-render writes the new primary hits of its listed targets into the cache. Depths >= 1 of a
// frame whose queues go to the secondary cache are not recorded at all (wavefront_loop.cpp). In a progressive
// accumulation (ACCUMULATING; it caches no hits) the primary segments and their shadow rays go to words 2-3 and their
// hit distances into the target's reach and range of hits (common.glsl accum_reach_word).
#include "gpu/shaders/common.glsl"
#include "gpu/segment_cells.h"
#include "gpu/shaders/reuse_cache.glsl"

layout(constant_id = 0) const bool LISTED = false;  // paths of listed targets (a partial re-render)
// A frame re-shaded from cached hits (a light edit): its closest-hit segments are those already in the masks, so only
// the shadow segments are added, to masks not cleared: the old shadow cells stay, a superset, still conservative.
// Only the rays it traced are added, one invocation per entry of the shadow queue: a ray that took its recorded
// occlusion (shade.comp OCCLUSION) is the ray whose cells were recorded when it was traced.
layout(constant_id = 1) const bool SHADOWS_ONLY = false;
// A progressive accumulation's passes: the primary segments and their shadow rays go to words 2-3, and the primary
// segments raise the target's reach and widen its range of hit distances (common.glsl accum_reach_word), by which
// mark_accumulated.comp tests them after a move.
layout(constant_id = 2) const bool ACCUMULATING = false;

layout(buffer_reference, std430, buffer_reference_align = 16) buffer HitCacheRef { uvec4 h[]; };

// The target of batch path `path`.
uint path_target(uint path) {
  uint entry = (pc.batchFirst + path) / FRAME.dims.z;
  return LISTED ? UintRef(FRAME.refine).v[FRAME.refineInfo.y + entry] : entry;
}

// SHADOWS_ONLY: the cells of shadow-queue entry i's ray, into words 2-3 for the shadow rays of cached primary hits.
void record_traced_shadow_ray(uint i) {
  if (i >= COUNTERS.shadowCount) return;
  uint slot = imageLoad(shadowQueueBuffer, int(i)).x & ~HT_SHADOW_MOVED_ONLY;
  uint target = path_target(slot / FRAME.scene.x);
  HtRay shadow = load_shadow_ray(slot);
  uvec2 cells = ht_segment_cells(shadow.origin, shadow.dir, shadow.tmin, shadow.tmax, FRAME.grid);
  uint word = 4u * target + (pc.depth == 0u && FRAME.primaryHits != 0ul ? 2u : 0u);
  if (cells.x != 0u) atomicOr(UintRef(FRAME.segmentMasks).v[word], cells.x);
  if (cells.y != 0u) atomicOr(UintRef(FRAME.segmentMasks).v[word + 1u], cells.y);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (SHADOWS_ONLY) {
    record_traced_shadow_ray(i);
    return;
  }
  if (i >= COUNTERS.queueCount[pc.queue]) return;
  uint path = queue_path(i);
  uint spp = FRAME.dims.z;
  uint target = path_target(path);
  HtRay ray = load_ray(pc.queue, i);
  HtHit hit = load_hit(i);
  bool cachedPrimary = pc.depth == 0u && FRAME.primaryHits != 0ul;
  float tEnd = hit.triId != HT_MISS ? hit.t : ray.tmax;
  uvec2 cells = ht_segment_cells(ray.origin, ray.dir, ray.tmin, tEnd, FRAME.grid);
  // Words 2-3 get the primary segment's cells and its shadow rays' in one atomic each (lavapipe runs an atomic on a
  // device address as a loop over the 8 lanes).
  uvec2 primaryCells = uvec2(0u);
  if (ACCUMULATING && pc.depth == 0u) {
    // An accumulation's primary segments: their cells to words 2-3 (their shadow rays' too, below), the target's
    // reach raised to this segment's end and its range of hit distances widened to this hit. After a move,
    // mark_accumulated.comp generates the rays of a target whose words 2-3 meet the moved cells again and tests them
    // exactly up to the reach, and the shadow rays from the box of their points between the nearest and farthest hit.
    primaryCells = cells;
    atomicMax(UintRef(FRAME.segmentMasks).v[accum_reach_word(target)], floatBitsToUint(max(tEnd, 0.0f)));
    if (hit.triId != HT_MISS) {
      atomicMax(UintRef(FRAME.segmentMasks).v[accum_near_hit_word(target)], ~floatBitsToUint(max(hit.t, 0.0f)));
      atomicMax(UintRef(FRAME.segmentMasks).v[accum_far_hit_word(target)], floatBitsToUint(max(hit.t, 0.0f)));
    }
    cells = uvec2(0u);
  }
  if (cachedPrimary) {  // words 2-3: the marking pass's quick reject before its exact test of the cached segments
    primaryCells = cells;
    cells = uvec2(0u);
    if (LISTED) {
      // A partial re-render's path that found its cached hit again has the same primary segment and shadow rays,
      // whose cells the marking pass kept in words 2-3 (dirty_list.glsl clear_dirty_target): nothing to add.
      uint framePath = target * spp + (pc.batchFirst + path) % spp;
      if (cached_primary_hit(framePath) == hit_bits(hit)) return;
      HitCacheRef(FRAME.primaryHits).h[framePath] = hit_bits(hit);
    }
  }
  uint lightCount = FRAME.scene.x;
  uvec2 shadowCells = uvec2(0u);
  for (uint l = 0u; l < lightCount; ++l) {
    uint slot = path * lightCount + l;
    // Live: emitted at this depth (occluded or not; traced, w = 1, or taken from the occlusion cache, w = 2).
    if (imageLoad(shadowContribBuffer, int(slot)).w != 0.0f) {
      HtRay shadow = load_shadow_ray(slot);
      shadowCells |= ht_segment_cells(shadow.origin, shadow.dir, shadow.tmin, shadow.tmax, FRAME.grid);
    }
  }
  if (cachedPrimary || (ACCUMULATING && pc.depth == 0u)) {  // the primary hits' shadow rays: tested exactly
    primaryCells |= shadowCells;
  } else {
    cells |= shadowCells;
  }
  if (primaryCells.x != 0u) atomicOr(UintRef(FRAME.segmentMasks).v[4u * target + 2u], primaryCells.x);
  if (primaryCells.y != 0u) atomicOr(UintRef(FRAME.segmentMasks).v[4u * target + 3u], primaryCells.y);
  if (cells.x != 0u) atomicOr(UintRef(FRAME.segmentMasks).v[4u * target], cells.x);
  if (cells.y != 0u) atomicOr(UintRef(FRAME.segmentMasks).v[4u * target + 1u], cells.y);
}
