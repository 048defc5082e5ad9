#version 460
#extension GL_GOOGLE_include_directive : require
// mark_dirty: the marking pass of a partial re-render (gpu/frame_reuse.h, docs/REUSE.md §4). Three modes, dispatched
// in this order by Renderer::Impl::runMarkingPass:
// - MARK_SECONDARY_ENTRIES (ReusePlan::secondaryExact): one invocation per entry of one cached queue of depth
//   pc.depth >= 1 (pc.batchCount entries from entry pc.queue of the cache, of the batch starting at path
//   pc.batchFirst). An entry whose segment, or a shadow ray from its hit, meets the padded moved bounds sets mask
//   words 0-1 of its target to all ones; targets whose words 0-1 already hold cells (re-traced after the cache was
//   filled) are left to those cells.
// - MARK_TARGETS: one invocation per HT_MARK_TARGETS_PER_INVOCATION (4) targets of the frame. A target whose mask
//   words 0-1 meet the moved bounds' cells (FRAME.moved.xy) is appended to the dirty list (count in word 2,
//   entries from word FRAME.refineInfo.y) and its mask cleared for the re-trace to record again (dirty_list.glsl
//   clear_dirty_target: words 0-1; 2-3 too in an accumulation). With the primary
//   rays and hits cached (FRAME.primaryHits != 0), a target whose words 2-3 (the cells of its primary segments and
//   their shadow rays) meet those cells is a candidate: appended to the candidate list (count in word 3, entries
//   from word FRAME.moved.z). So is one of a progressive accumulation (RESET_ACCUMULATION), whose words 2-3 hold the
//   cells of its primary segments alone; mark_accumulated.comp tests those candidates.
// - MARK_CANDIDATES: one invocation per HT_MARK_TARGETS_PER_INVOCATION candidates; a candidate is dirty when the
//   cached primary segment of one of its samples, or a shadow ray from that hit to a light (ht_shadow_meets_box),
//   meets the padded moved bounds (FRAME.movedLo, movedHi). A separate pass over a compact list, so that no
//   subgroup runs the exact tests for lanes that do not need them (a glow-sphere move on Portrait x0.5, 2.4 M
//   targets: 26 % candidates; MARK_TARGETS 48 ms, the candidates 44 ms, the secondary entries 31 ms on lavapipe, 2
//   vCPUs, 2026-12-03). Both MARK_TARGETS and MARK_CANDIDATES list their dirty targets with one subgroup scan per
//   invocation: the marking pass 224-227 -> 179-181 ms on that move (2026-12-04, AVX2 machine).
// List order varies with scheduling; a target's samples do not depend on it.
// CPU reference: gpu::markDirtyTargets (gpu/frame_reuse.h).
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu/segment_cells.h"
#include "gpu/shaders/reuse_cache.glsl"
#include "gpu/shaders/dirty_list.glsl"

// In a progressive accumulation after node moves (accumulation_pass.cpp resetMovedTargets): a dirty target's sums
// start over too (sum, n, half sum, half count = 0); the others keep theirs.
layout(constant_id = 0) const bool RESET_ACCUMULATION = false;
const uint MARK_TARGETS = 0u, MARK_SECONDARY_ENTRIES = 1u, MARK_CANDIDATES = 2u;
layout(constant_id = 1) const uint MODE = MARK_TARGETS;

// Every read goes through the reuse texel views (common.glsl, HT_BINDING_REUSE_*): lavapipe turns each 32-bit
// component of a device-address load into a loop over the 8 lanes, a texel fetch loads all lanes at once.

// Does the cached segment o + t d, t in [tmin, its hit or tmax], or a shadow ray from its hit to a light, meet the
// padded moved bounds?
bool cached_segment_meets_moved(vec3 o, float tmin, vec3 d, float tmax, uvec4 hit) {
  vec3 lo = moved_lo(), hi = moved_hi();
  vec4 ball0 = FRAME.movedBalls[0], ball1 = FRAME.movedBalls[1];  // (w < 0: none, the bounds alone)
  float tEnd = hit.y != HT_MISS ? uintBitsToFloat(hit.x) : tmax;
  if (ht_segment_meets_box(o, d, tmin, tEnd, lo, hi) && ht_segment_meets_balls(o, d, tmin, tEnd, ball0, ball1))
    return true;
  if (hit.y == HT_MISS) return false;
  vec3 p = ht_cached_hit_point(o, d, tEnd);
  float pErr = ht_cached_hit_error(o, d, tEnd);
  uint lightCount = FRAME.scene.x;
  for (uint l = 0u; l < lightCount; ++l) {
    GpuLight light = scene_light(l);
    if (ht_shadow_meets_box(p, pErr, light.position, light.direction.xyz, lo, hi) &&
        ht_shadow_meets_balls(p, pErr, light.position, light.direction.xyz, ball0, ball1))
      return true;
  }
  return false;
}

// Does a primary segment of one of the target's samples, or a shadow ray from its primary hit to a light, meet the
// moved bounds?
bool primary_meets_moved(uint target) {
  uint spp = FRAME.dims.z;
  for (uint s = 0u; s < spp; ++s) {
    uint path = target * spp + s;
    HtRay ray = cached_primary_ray(path);
    if (cached_segment_meets_moved(ray.origin, ray.tmin, ray.dir, ray.tmax, cached_primary_hit(path))) return true;
  }
  return false;
}

void mark_secondary_entry() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.batchCount) return;
  uint targets = FRAME.dims.w;  // a reusable frame is one chunk: all of its targets
  // FrameReuseState::secondaryRegion: the cache's `entries` rays (2 texels each), then their hits (1 texel), then
  // their path indices (4 per texel); this queue's entries from pc.queue on (its base in the cache).
  uint entries = FRAME.moved.w;
  uint e = pc.queue + i;
  uint target = (pc.batchFirst + texelFetch(reuseBounceTexels, int(3u * entries + e / 4u))[e % 4u]) / FRAME.dims.z;
  if (target >= targets) return;
  uvec4 mask = texelFetch(reuseMaskTexels, int(target));
  if ((mask.x | mask.y) != 0u) return;
  uvec4 a = texelFetch(reuseBounceTexels, int(2u * e)), b = texelFetch(reuseBounceTexels, int(2u * e + 1u));
  uvec4 hit = texelFetch(reuseBounceTexels, int(2u * entries + e));
  if (cached_segment_meets_moved(uintBitsToFloat(a.xyz), uintBitsToFloat(a.w), uintBitsToFloat(b.xyz),
                                 uintBitsToFloat(b.w), hit)) {
    atomicOr(UintRef(FRAME.segmentMasks).v[4u * target], 0xffffffffu);
    atomicOr(UintRef(FRAME.segmentMasks).v[4u * target + 1u], 0xffffffffu);
  }
}

void mark_target() {
  // Dispatched in slices of targets (pc.batchFirst: the slice's first; batchCount: all targets), each invocation
  // comparing HT_MARK_TARGETS_PER_INVOCATION consecutive targets and listing them with one subgroup scan per list.
  uint first = pc.batchFirst + HT_MARK_TARGETS_PER_INVOCATION * gl_GlobalInvocationID.x;
  uvec2 moved = FRAME.moved.xy;
  uint candidates = FRAME.moved.z;
  uint dirtyBits = 0u, candidateBits = 0u;  // bit k: target first + k
  for (uint k = 0u; k < HT_MARK_TARGETS_PER_INVOCATION; ++k) {
    if (first + k >= pc.batchCount) break;
    uvec4 mask = texelFetch(reuseMaskTexels, int(first + k));
    if (((mask.x & moved.x) | (mask.y & moved.y)) != 0u) {
      dirtyBits |= 1u << k;
    } else if (((mask.z & moved.x) | (mask.w & moved.y)) != 0u && candidates != 0u) {
      candidateBits |= 1u << k;
    }
  }
  append_bits(dirtyBits, 2u, FRAME.refineInfo.y, first);
  append_bits(candidateBits, 3u, candidates, first);
  for (uint bits = dirtyBits; bits != 0u; bits &= bits - 1u) {
    clear_dirty_target(first + uint(findLSB(bits)), RESET_ACCUMULATION);
  }
}

void mark_candidate() {
  // Dispatched in slices of candidates (pc.batchFirst: the slice's first; batchCount: all), each invocation testing
  // HT_MARK_TARGETS_PER_INVOCATION consecutive ones and listing the dirty ones with one subgroup scan.
  uint first = pc.batchFirst + HT_MARK_TARGETS_PER_INVOCATION * gl_GlobalInvocationID.x;
  uint candidates = FRAME.moved.z;
  uint dirty[HT_MARK_TARGETS_PER_INVOCATION];
  uint n = 0u;
  for (uint k = 0u; k < HT_MARK_TARGETS_PER_INVOCATION; ++k) {
    if (first + k >= pc.batchCount) break;
    uint target = reuse_list_word(candidates + first + k);
    if (primary_meets_moved(target)) dirty[n++] = target;
  }
  append_values(n, dirty, 2u, FRAME.refineInfo.y);
  for (uint k = 0u; k < n; ++k) clear_dirty_target(dirty[k], RESET_ACCUMULATION);
}

void main() {
  if (MODE != MARK_TARGETS) load_moved_view();  // the per-target pass compares cells only
  if (MODE == MARK_SECONDARY_ENTRIES) {
    mark_secondary_entry();
  } else if (MODE == MARK_CANDIDATES) {
    mark_candidate();
  } else {
    mark_target();
  }
}
