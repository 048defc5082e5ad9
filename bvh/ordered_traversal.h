// ordered_traversal.h - closest-hit traversal whose result does not depend on the tree: one source for the CPU
// (C++) and the GPU (GLSL), for a single BVH and for a two-level BVH (docs/BVH.md §9, docs/REUSE.md §3).
//
// The closest hit is defined as the least (t, triangle id) over all triangles the ray meets in [tmin, tmax],
// with t the value ht_intersect_triangle computes for the ray's own tmax. Every tree over the same world-space
// triangles therefore returns the same (t, id, u, v) bit for bit: a flattened BVH, a two-level BVH, a BVH
// rebuilt after an edit, whatever the visiting order. ht_trace_closest (bvh_traversal.h) is not order-free:
// its triangle test compares T against tmax*det with tmax = the current closest t, which can reject a
// triangle whose rounded t equals (or is an ulp below) the current one, and equal t keeps whichever triangle
// came last; its results differ between trees at the last ulp and on ties.
//
// Culling with the current best hit stays exact because it is loosened: boxes and the triangle pre-test use
// tCull = min(bestT * (1 + 2^-12), ray.tmax) instead of bestT. A triangle whose rounded t is <= bestT has
// T/det <= bestT (1 + 2 ulp), so the pre-test `T > tCull*det` never rejects it; its box is entered because the
// exact hit point lies in the box and the conservative slab test (slab_test.h) enters boxes up to tCull, as
// long as the rounded t is within 2^-12 (relative) of the exact one -- only a hit on a nearly degenerate
// projection could be off by more, which is why the tests also compare against a brute-force loop over all
// triangles. Among the triangles that pass, the least (t, id) wins. Cost: triangles up to 2^-12 beyond the
// best hit are still tested (negligible).
//
// Buffer access: as in bvh_traversal.h (HT_LOAD_NODE, HT_LOAD_TRI, HT_LOAD_NODE_LINK, HT_LOAD_TRI_ID) for the
// bottom-level nodes and triangle slots of all instances, concatenated; a BVH's node and slot indices are local
// and offset by its nodeBase and slotBase. The two-level trace also reads top-level nodes HT_LOAD_TOP_NODE(i)
// (a GpuBvhNode whose leaves list instance-table entries) and HT_LOAD_INSTANCE(i) (uvec4: nodeBase, slotBase,
// instance index, 0). C++ passes `const TwoLevelView& tl_` for them.
#ifndef HT_ORDERED_TRAVERSAL_H
#define HT_ORDERED_TRAVERSAL_H
#include "bvh/bvh_traversal.h"

#ifdef HT_GLSL
#define HT_TWO_LEVEL_PARAM
#define HT_TWO_LEVEL_ARG
#else
#define HT_TWO_LEVEL_PARAM const TwoLevelView &tl_,
#define HT_TWO_LEVEL_ARG tl_,
#ifndef HT_LOAD_TOP_NODE
#define HT_LOAD_TOP_NODE(i) tl_.topNodes[i]
#endif
#ifndef HT_LOAD_INSTANCE
#define HT_LOAD_INSTANCE(i) tl_.instances[i]
#endif
#endif

HT_SHARED_BEGIN

#ifndef HT_GLSL
// Host view of a two-level BVH: the top level and the bottom levels of all instances (blas).
struct TwoLevelView {
  const GpuBvhNode* topNodes;
  const uvec4* instances;  // per top-level leaf entry: (nodeBase, slotBase, instance index, 0)
  BvhView blas;
};
#endif

// 1 + 2^-12: the loosening of the current best t used for culling (see the header comment).
HT_CONST float HT_ORDERED_CULL_SCALE = 1.000244140625f;
// 1 - 2^-12: the same loosening of a lower bound on the hits still to be found (ht_trace_two_level_after_moves). A
// triangle whose rounded t is >= that bound lies in boxes whose conservative exit distance is at least the bound
// scaled by this.
HT_CONST float HT_ORDERED_NEAR_SCALE = 0.999755859375f;

// Culling distance for the current best hit (a miss culls at the ray's own tmax).
HT_INLINE float ht_ordered_cull_t(HT_IN(HtHit) best, float rayTmax) {
  if (best.triId == HT_MISS) return rayTmax;
  return min(best.t * HT_ORDERED_CULL_SCALE, rayTmax);
}

// True when (t, id) comes before the best hit so far: smaller t, or equal t and smaller triangle id.
HT_INLINE bool ht_hit_precedes(float t, uint id, HT_IN(HtHit) best) {
  return t < best.t || (t == best.t && id < best.triId);
}

// ht_hit_precedes during a walk, where best.triId holds the triangle *slot* (vec4 index) of the best hit: the
// triangle ids are loaded only on a tie of t (rare), not for every candidate -- a load per candidate cost about
// 10 % of trace time on lavapipe. The slot becomes the id once the walk ends (ht_resolve_slot_id).
HT_INLINE bool ht_slot_hit_precedes(HT_BVH_PARAM float t, uint slot, HT_IN(HtHit) best) {
  if (t != best.t) return t < best.t;
  return best.triId == HT_MISS || HT_LOAD_TRI_ID(slot) < HT_LOAD_TRI_ID(best.triId);
}

HT_INLINE void ht_resolve_slot_id(HT_BVH_PARAM HT_INOUT(HtHit) best) {
  if (best.triId != HT_MISS) best.triId = HT_LOAD_TRI_ID(best.triId);
}

// Ordered traversal state of one ray, carried across the BVHs of a two-level trace.
struct HtOrderedRay {
  HtSlabRay slab;
  HtWatertightRay tri;
  float tmax;   // the ray's own tmax
  uint leaves;  // the convex part the ray leaves on its outside, whose triangles do not count (0: none; §9.6)
};

HT_INLINE HtOrderedRay ht_make_ordered_ray(HT_IN(HtRay) ray, uint leaves) {
  HtOrderedRay r;
  r.slab = ht_make_slab_ray(ray.origin, ray.dir, ray.tmin);
  r.tri = ht_make_watertight_ray(ray.origin, ray.dir, ray.tmin);
  r.tmax = ray.tmax;
  r.leaves = leaves;
  return r;
}

// After both child boxes of a node were tested: the child to visit next (HT_REF_NONE: neither, pop the stack)
// and in `push` the farther child when both were hit (else HT_REF_NONE). Nearer child first.
HT_INLINE uint ht_order_children(bool hit0, bool hit1, float tEnter0, float tEnter1, uvec4 link, HT_OUT(uint) push) {
  uint ref0 = ht_child_ref(link.x, link.z);
  uint ref1 = ht_child_ref(link.y, link.w);
  push = HT_REF_NONE;
  if (hit0 && hit1) {
    bool swapOrder = tEnter1 < tEnter0;
    push = swapOrder ? ref0 : ref1;
    return swapOrder ? ref1 : ref0;
  }
  if (hit0 || hit1) return hit0 ? ref0 : ref1;
  return HT_REF_NONE;
}

// Tests the `count` triangle slots of a leaf starting at global slot `slot0` and keeps the least (t, id), with
// best.triId holding the slot of the best hit; `cull` follows the best hit (ht_ordered_cull_t).
// anyHit: stop at the first triangle hit within the ray's tmax (occlusion).
HT_INLINE void ht_ordered_leaf(HT_BVH_PARAM HT_IN(HtOrderedRay) r, uint slot0, uint count, bool anyHit,
                               HT_INOUT(HtHit) best, HT_INOUT(float) cull, HT_INOUT(uint) steps, uint stepLimit,
                               HT_INOUT(bool) overflow) {
  uint slot = slot0 * HT_TRI_STRIDE;
  uint slotEnd = slot + count * HT_TRI_STRIDE;
  for (; slot < slotEnd; slot += HT_TRI_STRIDE) {
    steps++;
    if (steps > stepLimit) {
      overflow = true;
      break;
    }
    vec3 v0 = vec3(HT_LOAD_TRI(slot).x, HT_LOAD_TRI(slot).y, HT_LOAD_TRI(slot).z);
    vec3 v1 = vec3(HT_LOAD_TRI(slot + 1u).x, HT_LOAD_TRI(slot + 1u).y, HT_LOAD_TRI(slot + 1u).z);
    vec3 v2 = vec3(HT_LOAD_TRI(slot + 2u).x, HT_LOAD_TRI(slot + 2u).y, HT_LOAD_TRI(slot + 2u).z);
    float t;
    float u;
    float v;
    if (ht_intersect_triangle(r.tri, v0, v1, v2, cull, t, u, v) && ht_slot_hit_precedes(HT_BVH_ARG t, slot, best) &&
        !ht_slot_in_part(HT_BVH_ARG slot, r.leaves)) {
      best.t = t;
      best.triId = slot;  // the id is looked up once the walk ends (ht_resolve_slot_id)
      best.u = u;
      best.v = v;
      cull = ht_ordered_cull_t(best, r.tmax);
      if (anyHit) break;
    }
  }
}

// Walks one BVH (root = local node 0 at nodeBase; leaves' slots offset by slotBase), updating best and cull.
// Aila & Laine's "while-while" form, as ht_trace (bvh_traversal.h): an inner loop descends through inner nodes
// until it reaches a leaf, then the leaf's triangles are tested; SIMD lanes (lavapipe runs 8 rays per vector)
// stay in the same phase longer than with one loop that alternates between nodes and leaves. Every iteration of
// every loop counts a step, so a loop lavapipe ended early has counted more than the step limit.
// Returns false when the walk did not finish (step limit, stack, or a driver that ended the loop).
// anyHit: the walk ends at the first hit (best.triId != HT_MISS afterwards).
HT_INLINE bool ht_ordered_bvh(HT_BVH_PARAM HT_IN(HtOrderedRay) r, uint nodeBase, uint slotBase, bool anyHit,
                              HT_INOUT(HtHit) best, HT_INOUT(float) cull, HT_INOUT(uint) steps, uint stepLimit) {
  uint stack[HT_BVH_MAX_DEPTH];
  uint sp = 0u;
  uint cur = 0u;
  bool overflow = false;
  bool finished = false;
  while (!overflow) {
    steps++;
    if (steps > stepLimit) {
      overflow = true;
      break;
    }
    while ((cur >> HT_REF_COUNT_SHIFT) == 0u) {
      steps++;
      if (steps > stepLimit) {
        overflow = true;
        break;
      }
      uint node = nodeBase + cur;
      bool hit0;
      bool hit1;
      float tEnter0;
      float tEnter1;
      ht_slab_boxes(r.slab, HT_LOAD_NODE(node).c0xy, HT_LOAD_NODE(node).c1xy, HT_LOAD_NODE(node).c01z, cull, hit0, hit1,
                    tEnter0, tEnter1);
      uvec4 link = uvec4(0u);
      if (hit0 || hit1) link = HT_LOAD_NODE_LINK(node);
      uint push;
      uint next = ht_order_children(hit0, hit1, tEnter0, tEnter1, link, push);
      if (push != HT_REF_NONE) {
        if (sp >= HT_BVH_MAX_DEPTH) {
          overflow = true;
          break;
        }
        stack[sp] = push;
        sp++;
      }
      if (next == HT_REF_NONE && sp != 0u) {
        sp--;
        next = stack[sp];
      }
      cur = next;  // HT_REF_NONE (count field 31) ends the descent: nothing left to visit
    }
    if (overflow) break;
    if (cur == HT_REF_NONE) {
      finished = true;
      break;
    }
    ht_ordered_leaf(HT_BVH_ARG r, slotBase + (cur & HT_REF_INDEX_MASK), cur >> HT_REF_COUNT_SHIFT, anyHit, best, cull,
                    steps, stepLimit, overflow);
    if (overflow) break;
    if (sp == 0u || (anyHit && best.triId != HT_MISS)) {
      finished = true;
      break;
    }
    sp--;
    cur = stack[sp];
  }
  return finished;
}

// Least (t, id) hit of a single BVH (nodes and slots from index 0) among the triangles outside convex part `leaves`
// (the part a ray leaving a surface leaves on its outside, tagged in the slots: bvh/gpu_node.h; 0 for none).
HT_INLINE HtTraceResult ht_trace_closest_ordered_leaving(HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit, uint leaves) {
  HtTraceResult res = ht_trace_miss(ray);
  if (!ht_ray_is_valid(ray)) return res;
  HtOrderedRay r = ht_make_ordered_ray(ray, leaves);
  float cull = r.tmax;
  uint steps = 0u;
  bool finished = ht_ordered_bvh(HT_BVH_ARG r, 0u, 0u, false, res.hit, cull, steps, stepLimit);
  ht_resolve_slot_id(HT_BVH_ARG res.hit);
  res.steps = steps;
  res.overflow = !finished;
  return res;
}

// Least (t, id) hit of a single BVH (nodes and slots from index 0).
HT_INLINE HtTraceResult ht_trace_closest_ordered(HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit) {
  return ht_trace_closest_ordered_leaving(HT_BVH_ARG ray, stepLimit, 0u);
}

// The least (t, id) of two hits of one ray (a miss comes after every hit).
HT_INLINE HtHit ht_least_hit(HT_IN(HtHit) a, HT_IN(HtHit) b) {
  if (b.triId != HT_MISS && ht_hit_precedes(b.t, b.triId, a)) return b;
  return a;
}

#if !defined(HT_GLSL) || defined(HT_LOAD_TOP_NODE)
// Walk of a two-level BVH: the top level over instance boxes, each instance's own BVH below; anyHit as in
// ht_ordered_bvh. (GLSL: only where the including shader defines HT_LOAD_TOP_NODE and HT_LOAD_INSTANCE.)
// `cull0`: the culling distance it starts from (the ray's tmax for a whole trace); `filtered`: the bottom levels of
// the instances whose indices are in `only` are walked whole, the others not at all, or with `enterOthers` from
// `othersNear` on: their boxes that end before it are culled (ht_trace_two_level_after_moves). Instance
// `leaves` - 1 is never entered (a ray leaving that convex part, ht_trace_two_level_any_leaving; 0 for none).
HT_INLINE HtTraceResult ht_two_level_walk_filtered(HT_TWO_LEVEL_PARAM HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit,
                                                   bool anyHit, float cull0, bool filtered, uvec4 only,
                                                   bool enterOthers, float othersNear, uint leaves) {
  HtTraceResult res = ht_trace_miss(ray);
  if (!ht_ray_is_valid(ray)) return res;
  HtOrderedRay r = ht_make_ordered_ray(ray, leaves);
  float tmin = r.slab.tmin;
  float cull = cull0;
  uint stack[HT_BVH_MAX_DEPTH];
  uint sp = 0u;
  uint cur = 0u;
  uint steps = 0u;
  bool overflow = false;
  bool finished = false;
  while (!overflow) {
    steps++;
    if (steps > stepLimit) {
      overflow = true;
      break;
    }
    if ((cur >> HT_REF_COUNT_SHIFT) != 0u) {
      uint first = cur & HT_REF_INDEX_MASK;
      uint end = first + (cur >> HT_REF_COUNT_SHIFT);
      for (uint e = first; e < end && !overflow; e++) {
        steps++;  // this loop's iterations count too (lavapipe's loop budget, docs/TOOLCHAIN.md §0)
        uvec4 inst = HT_LOAD_INSTANCE(e);
        bool other = filtered && inst.z != only.x && inst.z != only.y && inst.z != only.z && inst.z != only.w;
        if ((other && !enterOthers) || inst.z + 1u == leaves) continue;  // (leaves: instance index + 1)
        r.slab.tmin = other ? max(tmin, othersNear) : tmin;
        overflow = !ht_ordered_bvh(HT_BVH_ARG r, inst.x, inst.y, anyHit, res.hit, cull, steps, stepLimit);
        if (anyHit && res.hit.triId != HT_MISS) break;
      }
      r.slab.tmin = tmin;
      if (overflow) break;
      if (sp == 0u || (anyHit && res.hit.triId != HT_MISS)) {
        finished = true;
        break;
      }
      sp--;
      cur = stack[sp];
      continue;
    }
    bool hit0;
    bool hit1;
    float tEnter0;
    float tEnter1;
    ht_slab_boxes(r.slab, HT_LOAD_TOP_NODE(cur).c0xy, HT_LOAD_TOP_NODE(cur).c1xy, HT_LOAD_TOP_NODE(cur).c01z, cull,
                  hit0, hit1, tEnter0, tEnter1);
    uint push;
    uint next = ht_order_children(hit0, hit1, tEnter0, tEnter1, HT_LOAD_TOP_NODE(cur).link, push);
    if (push != HT_REF_NONE) {
      if (sp >= HT_BVH_MAX_DEPTH) {
        overflow = true;
        break;
      }
      stack[sp] = push;
      sp++;
    }
    if (next == HT_REF_NONE && sp == 0u) {
      finished = true;
      break;
    }
    if (next == HT_REF_NONE) {
      sp--;
      next = stack[sp];
    }
    cur = next;
  }
  ht_resolve_slot_id(HT_BVH_ARG res.hit);
  res.steps = steps;
  res.overflow = !finished;
  return res;
}

HT_INLINE HtTraceResult ht_two_level_walk(HT_TWO_LEVEL_PARAM HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit,
                                          bool anyHit) {
  return ht_two_level_walk_filtered(HT_TWO_LEVEL_ARG HT_BVH_ARG ray, stepLimit, anyHit, ray.tmax, false, uvec4(0u),
                                    false, 0.0f, 0u);
}

// Least (t, id) hit of a two-level BVH.
HT_INLINE HtTraceResult ht_trace_two_level_ordered(HT_TWO_LEVEL_PARAM HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit) {
  return ht_two_level_walk(HT_TWO_LEVEL_ARG HT_BVH_ARG ray, stepLimit, false);
}

// ht_trace_closest_ordered_leaving on a two-level BVH: the instance of part `leaves` (its index + 1) is not entered.
HT_INLINE HtTraceResult ht_trace_two_level_ordered_leaving(HT_TWO_LEVEL_PARAM HT_BVH_PARAM HT_IN(HtRay) ray,
                                                           uint stepLimit, uint leaves) {
  return ht_two_level_walk_filtered(HT_TWO_LEVEL_ARG HT_BVH_ARG ray, stepLimit, false, ray.tmax, false, uvec4(0u),
                                    false, 0.0f, leaves);
}

// The closest hit of a ray after some instances moved (`moved`: their instance indices, 0xFFFFFFFF for none), from
// its closest hit before the move, `kept` (docs/REUSE.md §4, "Primary rays that walk the moved instances alone").
// Every triangle outside the moved instances is where it was, and none of them came before `kept`.
// - `kept` on none of the moved instances (`keptMoved` false): the least (t, id) among the others is still `kept`.
//   The least among the moved instances' triangles where they are now comes from a walk that enters their bottom
//   levels alone, culled from the start at `kept`'s distance: a moved triangle with the same or a smaller t still
//   passes the loosened culling. The closest hit is the least of the two.
// - `kept` on a moved instance: the moved instances are walked whole, the others from `kept`'s distance on (loosened
//   by HT_ORDERED_NEAR_SCALE), since none of their triangles comes before it: their boxes that end sooner, such as
//   those around the origin of a ray leaving a surface, are culled.
// Either way the result is a whole trace's of the moved scene, bit for bit, because the closest hit is the
// order-free one. With `walk` false (`kept` unknown) it is the whole trace. `leaves` as for
// ht_trace_two_level_ordered_leaving (`kept` was found with the same).
HT_INLINE HtTraceResult ht_trace_two_level_after_moves(HT_TWO_LEVEL_PARAM HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit,
                                                       HT_IN(HtHit) kept, bool walk, bool keptMoved, uvec4 moved,
                                                       uint leaves) {
  bool keptStays = walk && !keptMoved;
  HtTraceResult res = ht_two_level_walk_filtered(HT_TWO_LEVEL_ARG HT_BVH_ARG ray, stepLimit, false,
                                                 keptStays ? ht_ordered_cull_t(kept, ray.tmax) : ray.tmax, walk, moved,
                                                 keptMoved, kept.t * HT_ORDERED_NEAR_SCALE, leaves);
  if (keptStays) res.hit = ht_least_hit(kept, res.hit);
  return res;
}

// Any hit of a two-level BVH within [tmin, tmax] (occlusion): the same triangles count as for ht_trace_any on the
// flattened BVH (ht_intersect_triangle with the ray's tmax); which one is reported depends on the tree.
HT_INLINE HtTraceResult ht_trace_two_level_any(HT_TWO_LEVEL_PARAM HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit) {
  return ht_two_level_walk(HT_TWO_LEVEL_ARG HT_BVH_ARG ray, stepLimit, true);
}

// ht_trace_any_leaving on a two-level BVH: a ray leaving convex part `leaves` (instance index + 1: a part is one
// instance) on the outside does not enter that instance's bottom level (docs/BVH.md §9.6). Occluded exactly when
// ht_trace_any_leaving finds a hit on the flattened BVH of the same tagged triangles.
HT_INLINE HtTraceResult ht_trace_two_level_any_leaving(HT_TWO_LEVEL_PARAM HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit,
                                                       uint leaves) {
  return ht_two_level_walk_filtered(HT_TWO_LEVEL_ARG HT_BVH_ARG ray, stepLimit, true, ray.tmax, false, uvec4(0u), false,
                                    0.0f, leaves);
}

// The occlusion of a ray after some instances moved (`moved` as for ht_trace_two_level_after_moves), for a ray that
// was unoccluded before the move (`wasUnoccluded`; docs/REUSE.md §4 "Shadow rays unoccluded before the move"): no
// unmoved triangle meets it and none has moved, so only the moved instances' bottom levels are walked. Otherwise the
// whole any-hit walk. Either way occluded exactly when the whole walk of the moved scene finds a hit (which hit may
// differ). `leaves` as for ht_trace_two_level_any_leaving, before and after the move.
HT_INLINE HtTraceResult ht_trace_two_level_any_after_moves(HT_TWO_LEVEL_PARAM HT_BVH_PARAM HT_IN(HtRay) ray,
                                                           uint stepLimit, bool wasUnoccluded, uvec4 moved,
                                                           uint leaves) {
  return ht_two_level_walk_filtered(HT_TWO_LEVEL_ARG HT_BVH_ARG ray, stepLimit, true, ray.tmax, wasUnoccluded, moved,
                                    false, 0.0f, leaves);
}
#endif

HT_SHARED_END
#endif
