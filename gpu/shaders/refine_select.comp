#version 460
#extension GL_GOOGLE_include_directive : require
// refine_select: lists the targets of the chunk whose contrast (gpu/adaptive_refinement.h) reaches the threshold
// FRAME.refineInfo.x (float bits), in target order whatever order the workgroups run in, so that a refined frame
// stays bit-identical from run to run. Stream compaction by per-subgroup counts and an exclusive scan (Harris,
// Sengupta & Owens, "Parallel prefix sum (scan) with CUDA", GPU Gems 3 ch. 39), one slot per subgroup and no
// workgroup barrier (lavapipe's barriers switch coroutines: twice the time of this pass). Buffer FRAME.refine:
//   [0, slots]                     per-slot counts, then (host) their exclusive scan with the total at [slots]
//   [slots + 1, + slots * S)       staging: slot s keeps its selected targets at (s * S + rank), S = refineInfo.z
//                                  = subgroup size x targets per pixel
//   [refineInfo.y, + targets)      the list
//   MODE 0, one invocation per pixel on a grid (pixels of a row) x rows x views: select its targets (3 subpixels, or
//           the pixel), count and stage (slot = linear workgroup * gl_NumSubgroups + subgroup; rows of 64-pixel
//           groups and pixel-major ranks keep the target order). One invocation per pixel rather than per subpixel
//           target: lavapipe pays a lot per invocation (select stage 228 -> 182 ms on Portrait, docs/BENCHMARKS.md);
//   MODE 1, one invocation per slot, after the host scan: move the slot's staged targets to list[scan[s] + rank],
//           and, in a progressive frame that keeps one (FRAME.accumList != 0), to the accumulation's list too;
//   MODE 2 (BY_ERROR only), one invocation per entry of the accumulation's list, the targets its last frame sampled:
//           select among them (slot = subgroup, S = subgroup size; the list is in target order, so the result is).
//           A target not on that list was left out by an earlier frame and stays out: its sums no longer change, so
//           the stop rule still holds for it (docs/REUSE.md §2).
// BY_ERROR also folds the targets it leaves out into the accumulation's settled statistics (FRAME.accumSettledStats),
// which the host combines with the show pass's statistics of the targets it shows.
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu/adaptive_refinement.h"

layout(constant_id = HT_SPEC_MODEL) const uint MODEL = HT_MODEL_LENTICULAR;
layout(constant_id = 1) const uint MODE = 0u;
// What selects a target: false = its contrast (adaptive refinement of a single frame), true = the stop rule of
// progressive accumulation on its stored sums (gpu/accumulation_error.h: the adaptive policy lists the targets that
// still need samples, docs/REUSE.md §1-§2).
layout(constant_id = 2) const bool BY_ERROR = false;

#include "gpu/shaders/accum_stats.glsl"

// Texel fetches, not image loads: lavapipe gathers all lanes of a fetch at once (gpu/shaders/bvh_access.glsl).
float channel(uint pixel, uint c) { return texelFetch(subpixelTexels, int(3u * pixel + c)).x; }

// Contrast of target (x, c) of row y of view `view` (MODE 0 runs on a grid of pixels x rows x views: no integer
// division by the image size, which the CPU driver cannot vectorise).
float target_contrast(uint x, uint c, uint y, uint view) {
  uint width = FRAME.dims.x;
  uint height = FRAME.dims.y;
  uint pixel = (view * height + y) * width + x;
  uint left = x > 0u ? pixel - 1u : pixel;
  uint right = x + 1u < width ? pixel + 1u : pixel;
  uint below = y > 0u ? pixel - width : pixel;
  uint above = y + 1u < height ? pixel + width : pixel;
  float contrast = 0.0f;
  for (uint k = 0u; k < 3u; ++k) {
    uint channelIndex = ht_model_has_subpixel_targets(MODEL) ? c : k;
    contrast = max(contrast, ht_refine_contrast(channel(pixel, channelIndex), channel(left, channelIndex),
                                                channel(right, channelIndex), channel(below, channelIndex),
                                                channel(above, channelIndex)));
    if (ht_model_has_subpixel_targets(MODEL)) break;  // a subpixel target shows one channel
  }
  return contrast;
}

// Whether chunk target `target` still needs samples under the stop rule (progressive accumulation); if not, it is
// folded into `settled`.
bool target_needs_samples(uint target, inout TargetStats settled) {
  AccumTarget a = load_accum_target(frame_global_target(target));
  float error = accum_target_error(a, target);
  bool needs = accum_needs_samples(a.n, error);
  if (!needs) fold_target_stats(settled, a.n, error, false);
  return needs;
}

// Stages the `count` targets of `selected` (bit c: target first + c) at this invocation's rank in slot `slot`, and
// stores the slot's count.
void stage_selected(uint slot, uint slots, uint first, uint selected) {
  UintRef refine = UintRef(FRAME.refine);
  uint count = bitCount(selected);
  uint at = slots + 1u + slot * FRAME.refineInfo.z + subgroupExclusiveAdd(count);
  for (uint c = 0u; c < 3u; ++c) {
    if ((selected & (1u << c)) != 0u) refine.v[at++] = first + c;
  }
  uint total = subgroupAdd(count);
  if (subgroupElect()) refine.v[slot] = total;
}

void main() {
  UintRef refine = UintRef(FRAME.refine);
  uint group = (gl_WorkGroupID.z * gl_NumWorkGroups.y + gl_WorkGroupID.y) * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint slots = gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_NumWorkGroups.z * gl_NumSubgroups;
  uint slot = group * gl_NumSubgroups + gl_SubgroupID;
  TargetStats settled = no_target_stats();
  if (MODE == 0u) {
    uint perPixel = ht_model_has_subpixel_targets(MODEL) ? 3u : 1u;
    uint x = gl_GlobalInvocationID.x;
    uint row = gl_GlobalInvocationID.z * FRAME.dims.y + gl_GlobalInvocationID.y;
    float threshold = uintBitsToFloat(FRAME.refineInfo.x);
    uint selected = 0u;  // bit c: target c of the pixel
    uint first = (row * FRAME.dims.x + x) * perPixel;
    if (x < FRAME.dims.x) {
      for (uint c = 0u; c < perPixel; ++c) {
        bool pick = BY_ERROR ? target_needs_samples(first + c, settled)
                             : target_contrast(x, c, gl_GlobalInvocationID.y, gl_GlobalInvocationID.z) >= threshold;
        if (pick) selected |= 1u << c;
      }
    }
    stage_selected(slot, slots, first, selected);
  } else if (MODE == 2u) {
    uint entry = gl_GlobalInvocationID.x;
    uint target = 0u;
    bool pick = false;
    if (entry < pc.batchCount) {
      target = UintRef(FRAME.accumList).v[entry];
      pick = target_needs_samples(target, settled);
    }
    stage_selected(slot, slots, target, pick ? 1u : 0u);
  } else {
    slot = gl_GlobalInvocationID.x;
    slots = pc.batchCount;
    if (slot >= slots) return;
    uint first = refine.v[slot];
    uint count = refine.v[slot + 1u] - first;
    uint staging = slots + 1u + slot * FRAME.refineInfo.z;
    bool keep = FRAME.accumList != 0ul;
    for (uint k = 0u; k < count; ++k) {
      uint target = refine.v[staging + k];
      refine.v[FRAME.refineInfo.y + first + k] = target;
      if (keep) UintRef(FRAME.accumList).v[first + k] = target;
    }
    return;
  }
  if (BY_ERROR) add_target_stats(settled, FRAME.accumSettledStats);
  if (group == 0u && gl_LocalInvocationIndex == 0u) COUNTERS.subgroupSize = gl_SubgroupSize;  // checked by the host
}
