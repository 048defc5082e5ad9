#version 460
#extension GL_GOOGLE_include_directive : require
// trace_closest: one closest-hit traversal per invocation (one ray per invocation per dispatch: lavapipe ends
// every loop of an invocation after 65,535 iterations in total, docs/TOOLCHAIN.md §0). Rays past the step limit are
// counted in overflowCount, which the host turns into an error. The closest hit is the order-free one, the least
// (t, triangle id) (bvh/ordered_traversal.h, docs/BVH.md §9.3): the same for every tree over the same triangles,
// so a rebuilt, refitted or two-level BVH gives the same frame bits. Every loop iteration of the traversal counts a
// step, so a loop lavapipe cut short has used more than HT_TRAVERSAL_STEP_LIMIT steps and sets overflow.
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu/shaders/bvh_access.glsl"
#include "bvh/ordered_traversal.h"
#include "gpu/segment_cells.h"

// The primary rays of a partial re-render with the primary hits cached (ReusePlan::primaryCached; docs/REUSE.md §4):
// a ray whose cached segment, up to its cached hit, does not meet the padded moved bounds has that same hit in the
// edited scene (reuse_cache.glsl), so it takes the cached hit and is not traced. Most re-traced targets are
// re-traced for a shadow or a reflection, not for their primary ray. A ray that is traced and hits elsewhere now
// has its path's recorded shadow occlusion at this depth cleared: shade.comp (KEPT_SEGMENTS) takes a recorded
// occlusion only where the word still holds one, without testing the primary segment again. One that finds the
// cached hit again, bit for bit (it crossed the moved bounds where the node is in neither place), keeps the word:
// shade then builds the same surface point and the same shadow rays from it as the frame that recorded them.
// On a two-level BVH whose moved instances are known (FrameBlock::movedInstanceIds), a ray that is traced walks from
// its cached hit (ht_trace_two_level_after_moves): every other triangle is where it was when that hit was found.
// Cached hit on none of them: only their bottom levels, culled at the cached hit, and the least of the two. On one
// of them: theirs whole, the others' only beyond the cached hit.
layout(constant_id = 0) const bool REUSE_PRIMARY = false;
// The bounce rays (depths >= 1) of a partial re-render whose bounce cache holds links (ReusePlan::bounceLinks,
// docs/REUSE.md §4 "Bounce rays that take their cached hits"): a ray that is its path's cached ray at this depth,
// bit for bit, takes the cached hit when its segment to that hit avoids the padded moved bounds, and else walks
// from that hit, as a primary ray does. A re-traced path is a pure function of its target, sample and the scene, so
// until the first segment a move changed it rebuilds the rays the cache holds; the bit test needs no reasoning
// about the path's history.
layout(constant_id = 1) const bool REUSE_BOUNCES = false;

#include "gpu/shaders/reuse_cache.glsl"

// Is the cached hit (its bits) on one of the moved instances?
bool cached_hit_moved(uvec4 cachedHit) {
  uvec4 ids = FRAME.movedInstanceIds;
  for (uint k = 0u; k < HT_MAX_WALKED_INSTANCES && ids[k] != 0xFFFFFFFFu; k++) {
    uvec4 tris = FRAME.movedTriangles[k];
    if (cachedHit.y - tris.x < tris.y) return true;  // a miss (HT_MISS) is on none
  }
  return false;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool inQueue = i < COUNTERS.queueCount[pc.queue];
  uint steps = 0u;
  bool overflow = false;
  uint path = 0u;
  uvec4 cachedHit = uvec4(0u);
  bool walk = false;  // cachedHit is the ray's hit before the move: walk from it (ht_trace_two_level_after_moves)
  if (REUSE_PRIMARY && inQueue) {  // queue 0 entry i is path i of the batch
    load_moved_view();
    path = listed_frame_path(i);
    cachedHit = cached_primary_hit(path);
    if (!cached_primary_meets_moved(path, cachedHit)) {
      store_hit(i, hit_of_bits(cachedHit));
      inQueue = false;  // not traced
    }
    walk = moved_instances_known();
  }
  HtRay ray;
  if (inQueue) ray = load_ray(pc.queue, i);
  if (REUSE_BOUNCES && inQueue) {
    load_moved_view();
    uint e = cached_bounce_entry(listed_frame_path(queue_path(i)));
    if (e != HT_NO_BOUNCE && is_cached_bounce_ray(e, ray)) {
      cachedHit = cached_bounce_hit(e);
      if (!segment_to_hit_meets_moved(ray, cachedHit)) {
        store_hit(i, hit_of_bits(cachedHit));
        inQueue = false;  // not traced
      }
      walk = moved_instances_known();
    }
  }
  if (inQueue) {
    // A bounce ray that leaves a convex part on its outside skips it (shade.comp; docs/BVH.md §9.6).
    uint leaves = pc.depth == 0u ? 0u : load_queue_leaves(pc.queue, i);  // (primary rays, ray batches: none)
    HtTraceResult r;
    if ((REUSE_PRIMARY || REUSE_BOUNCES) && TWO_LEVEL) {
      // One walk for every lane (lavapipe runs both sides of a divergent branch): whole, or from the cached hit.
      r = ht_trace_two_level_after_moves(ray, FRAME.scene.z, hit_of_bits(cachedHit), walk,
                                         cached_hit_moved(cachedHit), FRAME.movedInstanceIds, leaves);
    } else if (TWO_LEVEL) {
      r = ht_trace_two_level_ordered_leaving(ray, FRAME.scene.z, leaves);
    } else {
      r = ht_trace_closest_ordered_leaving(ray, FRAME.scene.z, leaves);
    }
    store_hit(i, r.hit);
    steps = r.steps;
    overflow = r.overflow;
    if (REUSE_PRIMARY && FRAME.shadowOcclusion != 0ul && hit_bits(r.hit) != cachedHit) {
      UintRef(FRAME.shadowOcclusion).v[occlusion_word_of_frame_path(path)] = 0u;
    }
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
