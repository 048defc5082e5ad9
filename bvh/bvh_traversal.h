// bvh_traversal.h - robust closest-hit and any-hit BVH traversal, one source for the CPU reference (C++) and the
// GPU compute kernel (GLSL).
//
// Structure: Aila & Laine 2009 "while-while" loop (docs/BVH.md §2.4, §4): an inner loop descends through inner
// nodes, testing BOTH child boxes of a 64 B GpuBvhNode at once (slab_test.h) and visiting the nearer child
// first while the farther one goes onto a private stack of HT_BVH_MAX_DEPTH entries; a second loop tests the
// triangles of the leaf reached (watertight_triangle.h). The builder bounds the leaf depth by
// HT_BVH_MAX_DEPTH and at most one entry is pushed per level, so the stack cannot overflow; a push onto a
// full stack is nevertheless reported as overflow, never dropped (docs/BVH.md §2.2 caveat on tinybvh's shaders).
//
// Step counting: every iteration of every loop increments `steps`; once steps exceed `stepLimit` the
// traversal stops with overflow = true. lavapipe silently ends a shader's loops after 65,535 iterations in
// total per invocation (docs/TOOLCHAIN.md §0), so the GPU kernel passes a limit below that and the host turns
// overflow into an error instead of a silent miss. Rays with a NaN/Inf origin or direction, a zero direction
// or NaN tmin/tmax return a miss after 0 steps.
//
// Buffer access goes through macros so GLSL and C++ share this code:
//   C++ : functions take `HT_BVH_PARAM` = `const BvhView& bvh_,` first; HT_LOAD_NODE(i) = bvh_.nodes[i],
//         HT_LOAD_TRI(i) = bvh_.triangles[i] (vec4).
//   GLSL: HT_BVH_PARAM / HT_BVH_ARG are empty; the including shader defines HT_LOAD_NODE(i) (a GpuBvhNode)
//         and HT_LOAD_TRI(i) (a vec4) before including this header.
//
// Stack / reference encoding: a child reference is packed into one uint as (count << 27) | index, count 0 =
// inner node index, count 1..16 = leaf of `count` triangle slots starting at slot `index`. gpu_layout.cpp
// guarantees index < 2^27 and count <= HT_MAX_LEAF_SIZE.
#ifndef HT_BVH_TRAVERSAL_H
#define HT_BVH_TRAVERSAL_H
#include "common/glsl_cpp.h"
#include "bvh/float_bounds.h"
#include "bvh/gpu_node.h"
#include "bvh/ray_types.h"
#include "bvh/slab_test.h"
#include "bvh/watertight_triangle.h"

HT_SHARED_BEGIN

struct HtTraceResult {
  HtHit hit;      // triId == HT_MISS on a miss (t = ray.tmax then)
  uint steps;     // loop iterations used (all loops together)
  bool overflow;  // step limit exceeded (or stack full): the hit record is incomplete
};

HT_CONST uint HT_REF_COUNT_SHIFT = 27u;
HT_CONST uint HT_REF_INDEX_MASK = 0x07FFFFFFu;  // node indices and triangle slots must stay below this
HT_CONST uint HT_MAX_LEAF_SIZE = 16u;           // largest triangle count of a leaf
HT_CONST uint HT_REF_NONE = 0xFFFFFFFFu;        // "stack empty": count field 31 > HT_MAX_LEAF_SIZE

#ifndef HT_GLSL
// Host view of the two buffers the traversal reads.
struct BvhView {
  const GpuBvhNode* nodes;
  const vec4* triangles;  // HT_TRI_STRIDE vec4 per slot
};
#endif

HT_SHARED_END

#ifdef HT_GLSL
#define HT_BVH_PARAM
#define HT_BVH_ARG
#if !defined(HT_LOAD_NODE) || !defined(HT_LOAD_TRI)
#error "define HT_LOAD_NODE(i) and HT_LOAD_TRI(i) before including bvh/bvh_traversal.h"
#endif
#else
#define HT_BVH_PARAM const BvhView &bvh_,
#define HT_BVH_ARG bvh_,
#ifndef HT_LOAD_NODE
#define HT_LOAD_NODE(i) bvh_.nodes[i]
#endif
#ifndef HT_LOAD_TRI
#define HT_LOAD_TRI(i) bvh_.triangles[i]
#endif
#endif

// Optional finer accessors; a shader reading through float-typed texel fetches overrides them so that the
// integer fields (child links, triangle id bits, which are float denormals) never pass through a float path.
#ifndef HT_LOAD_NODE_LINK
#define HT_LOAD_NODE_LINK(i) HT_LOAD_NODE(i).link
#endif
#ifndef HT_LOAD_TRI_ID
#define HT_LOAD_TRI_ID(slot) floatBitsToUint(HT_LOAD_TRI(slot).w)
#endif

HT_SHARED_BEGIN

// A ray is traced only if origin and direction are finite, the direction is not zero and tmin <= tmax
// (false for NaN); tmax = +inf is allowed.
HT_INLINE bool ht_ray_is_valid(HT_IN(HtRay) ray) {
  bool finiteOrigin =
      abs(ray.origin.x) <= HT_FLOAT_MAX && abs(ray.origin.y) <= HT_FLOAT_MAX && abs(ray.origin.z) <= HT_FLOAT_MAX;
  bool finiteDir = abs(ray.dir.x) <= HT_FLOAT_MAX && abs(ray.dir.y) <= HT_FLOAT_MAX && abs(ray.dir.z) <= HT_FLOAT_MAX;
  bool nonZeroDir = ray.dir.x != 0.0f || ray.dir.y != 0.0f || ray.dir.z != 0.0f;
  return finiteOrigin && finiteDir && nonZeroDir && ray.tmin <= ray.tmax;
}

HT_INLINE HtTraceResult ht_trace_miss(HT_IN(HtRay) ray) {
  HtTraceResult res;
  res.hit.t = ray.tmax;
  res.hit.triId = HT_MISS;
  res.hit.u = 0.0f;
  res.hit.v = 0.0f;
  res.steps = 0u;
  res.overflow = false;
  return res;
}

// Packed child reference k (0 or 1) of a node: (count << 27) | index.
HT_INLINE uint ht_child_ref(uint index, uint count) { return (count << HT_REF_COUNT_SHIFT) | index; }

// Is triangle slot `slot` (its first vec4's index) one of convex part `part`'s (never for part 0)? Read only for a
// triangle the ray meets: vertex 1's .w holds the part (gpu_node.h), a float, exact below 2^24.
HT_INLINE bool ht_slot_in_part(HT_BVH_PARAM uint slot, uint part) {
  return part != 0u && HT_LOAD_TRI(slot + 1u).w == float(part);
}

// Shared body of closest-hit (anyHit = false) and early-exit any-hit (anyHit = true) traversal.
// The GLSL compiler inlines it with a constant anyHit, so each variant keeps only its own branch.
// `leaves`: the convex part the ray leaves (ht_trace_any_leaving), whose triangles do not count; 0 for none.
HT_INLINE HtTraceResult ht_trace_leaving(HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit, bool anyHit, uint leaves) {
  HtTraceResult res = ht_trace_miss(ray);
  if (!ht_ray_is_valid(ray)) return res;
  HtSlabRay slabRay = ht_make_slab_ray(ray.origin, ray.dir, ray.tmin);
  HtWatertightRay triRay = ht_make_watertight_ray(ray.origin, ray.dir, ray.tmin);
  float tmax = ray.tmax;

  uint stack[HT_BVH_MAX_DEPTH];
  uint sp = 0u;
  uint cur = 0u;  // the root, inner node 0 (gpu_layout.cpp always emits one)
  uint steps = 0u;
  bool overflow = false;
  bool done = false;
  bool finished = false;
  while (!done) {
    steps++;
    if (steps > stepLimit) {
      overflow = true;
      break;
    }
    // Descend through inner nodes until `cur` is a leaf or the stack is exhausted.
    while ((cur >> HT_REF_COUNT_SHIFT) == 0u) {
      steps++;
      if (steps > stepLimit) {
        overflow = true;
        break;
      }
      // Members are loaded separately, the child links only when a child box is hit: Mesa 22.3's gallivm
      // turns every 32-bit component of a global/SSBO load into a loop over the 8 lanes that skips inactive
      // ones (lp_bld_nir_soa.c emit_load_global / emit_load_mem), so fewer components loaded is faster.
      bool hit0;
      bool hit1;
      float tEnter0;
      float tEnter1;
      ht_slab_boxes(slabRay, HT_LOAD_NODE(cur).c0xy, HT_LOAD_NODE(cur).c1xy, HT_LOAD_NODE(cur).c01z, tmax, hit0, hit1,
                    tEnter0, tEnter1);
      uvec4 link = uvec4(0u);
      if (hit0 || hit1) link = HT_LOAD_NODE_LINK(cur);
      uint ref0 = ht_child_ref(link.x, link.z);
      uint ref1 = ht_child_ref(link.y, link.w);
      if (hit0 && hit1) {
        bool swapOrder = tEnter1 < tEnter0;
        if (sp >= HT_BVH_MAX_DEPTH) {
          overflow = true;
          break;
        }
        stack[sp] = swapOrder ? ref0 : ref1;
        sp++;
        cur = swapOrder ? ref1 : ref0;
      } else if (hit0 || hit1) {
        cur = hit0 ? ref0 : ref1;
      } else if (sp == 0u) {
        cur = HT_REF_NONE;
      } else {
        sp--;
        cur = stack[sp];
      }
    }
    if (overflow) break;
    if (cur == HT_REF_NONE) {
      finished = true;
      break;
    }

    // Leaf: test its triangles inline.
    uint slot = (cur & HT_REF_INDEX_MASK) * HT_TRI_STRIDE;
    uint slotEnd = slot + (cur >> HT_REF_COUNT_SHIFT) * HT_TRI_STRIDE;
    for (; slot < slotEnd; slot += HT_TRI_STRIDE) {
      steps++;
      if (steps > stepLimit) {
        overflow = true;
        break;
      }
      // Only x, y, z: the triangle id in v0.w is read once after the loop, for the final hit.
      vec3 v0 = vec3(HT_LOAD_TRI(slot).x, HT_LOAD_TRI(slot).y, HT_LOAD_TRI(slot).z);
      vec3 v1 = vec3(HT_LOAD_TRI(slot + 1u).x, HT_LOAD_TRI(slot + 1u).y, HT_LOAD_TRI(slot + 1u).z);
      vec3 v2 = vec3(HT_LOAD_TRI(slot + 2u).x, HT_LOAD_TRI(slot + 2u).y, HT_LOAD_TRI(slot + 2u).z);
      float t;
      float u;
      float v;
      if (ht_intersect_triangle(triRay, v0, v1, v2, tmax, t, u, v) && !ht_slot_in_part(HT_BVH_ARG slot, leaves)) {
        tmax = t;
        res.hit.t = t;
        res.hit.triId = slot;  // slot of the hit for now; replaced by the triangle id below
        res.hit.u = u;
        res.hit.v = v;
        if (anyHit) {
          done = true;
          break;
        }
      }
    }
    if (overflow) break;
    if (done || sp == 0u) {
      finished = true;
      break;
    }
    sp--;
    cur = stack[sp];
  }
  // Legitimate exits: the stack ran empty or an any-hit was found; the step limit sets overflow. Anything
  // else means the driver ended the loop behind our back -- lavapipe stops every loop of an invocation after
  // 65,535 iterations in total and counts more iterations than `steps` does -- so report it as overflow too.
  if (!finished) overflow = true;
  // The triangle id is read once, for the final hit, rather than for every triangle tested.
  if (res.hit.triId != HT_MISS) res.hit.triId = HT_LOAD_TRI_ID(res.hit.triId);
  res.steps = steps;
  res.overflow = overflow;
  return res;
}

HT_INLINE HtTraceResult ht_trace(HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit, bool anyHit) {
  return ht_trace_leaving(HT_BVH_ARG ray, stepLimit, anyHit, 0u);
}

// Closest hit along [ray.tmin, ray.tmax].
HT_INLINE HtTraceResult ht_trace_closest(HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit) {
  return ht_trace(HT_BVH_ARG ray, stepLimit, false);
}

// Any hit along [ray.tmin, ray.tmax] (occlusion): hit.triId != HT_MISS when occluded; stops at the first hit.
HT_INLINE HtTraceResult ht_trace_any(HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit) {
  return ht_trace(HT_BVH_ARG ray, stepLimit, true);
}

// Any hit of a ray that leaves the surface of convex part `leaves` (the tag in its slots: vertex 1's .w, gpu_node.h;
// docs/BVH.md §9.6) on the outside: the part's triangles do not count. The part cannot meet such a ray, so the
// occlusion is the same, less any rounding self-hit; the two-level walk skips the part's bottom level instead.
HT_INLINE HtTraceResult ht_trace_any_leaving(HT_BVH_PARAM HT_IN(HtRay) ray, uint stepLimit, uint leaves) {
  return ht_trace_leaving(HT_BVH_ARG ray, stepLimit, true, leaves);
}

HT_SHARED_END
#endif
