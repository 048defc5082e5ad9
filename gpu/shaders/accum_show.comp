#version 460
#extension GL_GOOGLE_include_directive : require
// accum_show: the show pass of a progressive frame (gpu/accumulator.h, docs/REUSE.md §1-§2), over the targets of
// its chunk or over the targets it sampled. Writes the shown value sum / n into the subpixel buffer -- the expression
// resolve.comp uses for a single frame, so a progressive frame of k*N samples shows the bits of one frame at k*N spp
// -- and folds the target's error estimate and stop rule (gpu/accumulation_error.h) into the frame's AccumStats
// (accum_stats.glsl).
#include "gpu/shaders/common.glsl"

layout(constant_id = HT_SPEC_MODEL) const uint MODEL = HT_MODEL_LENTICULAR;
// false: the chunk's targets pc.batchFirst.. in order; true: the entries pc.batchFirst.. of the accumulation's list
// (FRAME.accumList), the targets this frame sampled. The others' sums did not change since a frame of this
// accumulation last showed them, so the subpixel buffer still holds their values (accumulation_pass.cpp decides).
layout(constant_id = 1) const bool LISTED = false;

#include "gpu/shaders/accum_stats.glsl"

// Shows target `target` and folds it into `stats`.
void show_target(uint target, inout TargetStats stats) {
  AccumTarget a = load_accum_target(frame_global_target(target));
  vec3 value = accum_mean(a);
  float error = accum_target_error(a, target);
  bool finite = !(any(isnan(value)) || any(isinf(value)));
  if (!finite) {
    atomicAdd(COUNTERS.nanCount, 1u);
    value = vec3(0.0f);
  }
  if (ht_model_has_subpixel_targets(MODEL)) {
    uint c = target % 3u;
    imageStore(subpixelBuffer, int(target), vec4(c == 0u ? value.x : (c == 1u ? value.y : value.z)));
  } else {
    imageStore(subpixelBuffer, int(3u * target), vec4(value.x));
    imageStore(subpixelBuffer, int(3u * target + 1u), vec4(value.y));
    imageStore(subpixelBuffer, int(3u * target + 2u), vec4(value.z));
  }
  fold_target_stats(stats, a.n, error, accum_needs_samples(a.n, error));
}

void main() {
  // HT_ACCUM_SHOW_TARGETS_PER_INVOCATION consecutive targets (or list entries) per invocation: lavapipe pays much
  // per invocation and per subgroup operation, and showing a target is a few loads and stores. Dispatched in
  // slices: pc.batchFirst is the slice's first target or entry, pc.batchCount its count.
  uint first = HT_ACCUM_SHOW_TARGETS_PER_INVOCATION * gl_GlobalInvocationID.x;
  TargetStats stats = no_target_stats();
  for (uint k = 0u; k < HT_ACCUM_SHOW_TARGETS_PER_INVOCATION; ++k) {
    if (first + k >= pc.batchCount) break;
    uint at = pc.batchFirst + first + k;
    show_target(LISTED ? UintRef(FRAME.accumList).v[at] : at, stats);
  }
  add_target_stats(stats, FRAME.accumStats);
}
