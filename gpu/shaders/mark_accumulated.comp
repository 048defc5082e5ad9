#version 460
#extension GL_GOOGLE_include_directive : require
// mark_accumulated: the exact test of the marking pass in a progressive accumulation after node moves (docs/REUSE.md
// §4 in streams; dispatched by Renderer::Impl::runMarkingPass after mark_dirty.comp's MARK_TARGETS, with
// RESET_ACCUMULATION). One invocation per candidate: a target whose other segments' cells (mask words 0-1) avoid the
// moved bounds' cells but whose primary segments' or their shadow rays' cells (words 2-3) meet them. An accumulation
// keeps no primary rays or hits (up to max spp of them per target), so its n samples' rays are generated again, with
// raygen's own code (primary_ray.glsl), and tested against the padded moved bounds (FRAME.movedLo, movedHi):
// - each segment from the ray's origin to the target's reach (the farthest primary hit or miss of its samples,
//   common.glsl accum_reach_word): a target none of whose segments meets them kept every primary hit, since every
//   triangle of the moved nodes lies inside those bounds before and after, every other is unchanged, and the closest
//   hit is the order-free one;
// - the shadow rays from its primary hits to each light: every hit lies on its ray between the target's nearest and
//   farthest hit distance, so within the box of those points of all its rays (grown by the hit points' rounding,
//   ht_cached_hit_error), and ht_box_shadow_meets_box bounds every shadow ray from that box.
// A target that passes both keeps its sums (its other segments' cells already missed the moved ones); the others
// restart. The bounds are padded by HT_GRID_PAD cells, far above the rounding by which these rays can differ from
// raygen's.
// CPU reference: gpu::markAccumulatedTargets (gpu/frame_reuse.h).
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu/shaders/primary_ray.glsl"  // constants 0-2: raygen's
#include "gpu/segment_cells.h"
#include "gpu/shaders/reuse_cache.glsl"
#include "gpu/shaders/dirty_list.glsl"

// Does the primary segment of one of the target's samples so far, or a shadow ray from one of their hits, meet the
// padded moved bounds?
bool samples_meet_moved(uint target) {
  uint n = accum_samples_so_far(frame_global_target(target));
  if (n > HT_MARK_MAX_SAMPLES) return true;  // lavapipe's loop budget (segment_cells.h): restart, never miss one
  float reach = uintBitsToFloat(reuse_mask_word(accum_reach_word(target)));
  uint nearWord = reuse_mask_word(accum_near_hit_word(target));
  bool hits = nearWord != 0u;
  float near = uintBitsToFloat(~nearWord), far = uintBitsToFloat(reuse_mask_word(accum_far_hit_word(target)));
  vec3 pLo = vec3(HT_GRID_T_INFINITY), pHi = vec3(-HT_GRID_T_INFINITY);
  float pErr = 0.0f;
  for (uint k = 0u; k < n; ++k) {
    HtRay ray = primary_ray(target, k, 1u, true);
    if (ht_segment_meets_box(ray.origin, ray.dir, ray.tmin, reach, moved_lo(), moved_hi())) return true;
    vec3 a = ht_cached_hit_point(ray.origin, ray.dir, near), b = ht_cached_hit_point(ray.origin, ray.dir, far);
    pLo = min(pLo, min(a, b));
    pHi = max(pHi, max(a, b));
    pErr = max(pErr, ht_cached_hit_error(ray.origin, ray.dir, far));
  }
  for (uint l = 0u; hits && l < FRAME.scene.x; ++l) {
    GpuLight light = scene_light(l);
    if (ht_box_shadow_meets_box(pLo, pHi, pErr, light.position, light.direction.xyz, moved_lo(), moved_hi())) return true;
  }
  return false;
}

void main() {
  load_moved_view();
  uint i = pc.batchFirst + gl_GlobalInvocationID.x;  // dispatched in slices of candidates; batchCount: all
  bool dirty = false;
  uint target = 0u;
  if (i < pc.batchCount) {
    target = reuse_list_word(FRAME.moved.z + i);
    dirty = samples_meet_moved(target);
  }
  mark_dirty(dirty, target, true);
}
