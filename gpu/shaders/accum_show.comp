#version 460
#extension GL_GOOGLE_include_directive : require
// accum_show: one invocation per target of the chunk of a progressive frame (gpu/accumulator.h, docs/REUSE.md
// §1-§2). Writes the shown value sum / n into the subpixel buffer -- the expression resolve.comp uses for a single
// frame, so a progressive frame of k*N samples shows the bits of one frame at k*N spp -- and folds the target's error
// estimate and stop rule (gpu/accumulation_error.h) into the frame's AccumStats.
#include "gpu/shaders/common.glsl"
#include "gpu/accumulation_error.h"
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require

layout(constant_id = HT_SPEC_MODEL) const uint MODEL = HT_MODEL_LENTICULAR;

// The stop-rule statistics of the targets one invocation shows, reduced per subgroup at the end.
struct ShowStats {
  uint unconverged, maxErrorBits, minSamples, maxSamples;
};

// Shows target `target` and folds it into `stats`.
void show_target(uint target, inout ShowStats stats) {
  AccumTarget a = AccumRef(FRAME.accumTargets).t[frame_global_target(target)];
  vec3 value = a.n > 0u ? a.sum / float(a.n) : vec3(0.0f);
  bool subpixel = ht_model_has_subpixel_targets(MODEL);
  uint c = target % 3u;
  vec3 mask = subpixel ? vec3(c == 0u ? 1.0f : 0.0f, c == 1u ? 1.0f : 0.0f, c == 2u ? 1.0f : 0.0f) : vec3(1.0f);
  vec3 halfMean = a.halfN > 0u ? a.halfSum / float(a.halfN) : vec3(0.0f);
  float error = ht_accum_error(value, halfMean, a.halfN, mask);
  bool finite = !(any(isnan(value)) || any(isinf(value)));
  if (!finite) {
    atomicAdd(COUNTERS.nanCount, 1u);
    value = vec3(0.0f);
  }
  if (subpixel) {
    imageStore(subpixelBuffer, int(target), vec4(c == 0u ? value.x : (c == 1u ? value.y : value.z)));
  } else {
    imageStore(subpixelBuffer, int(3u * target), vec4(value.x));
    imageStore(subpixelBuffer, int(3u * target + 1u), vec4(value.y));
    imageStore(subpixelBuffer, int(3u * target + 2u), vec4(value.z));
  }
  bool needs = ht_accum_needs_samples(a.n, error, FRAME.accum.z, FRAME.accum.w, uintBitsToFloat(FRAME.accum.y));
  stats.unconverged += needs ? 1u : 0u;
  stats.maxErrorBits = max(stats.maxErrorBits, isnan(error) ? 0u : floatBitsToUint(min(error, HT_ACCUM_UNKNOWN_ERROR)));
  stats.minSamples = min(stats.minSamples, a.n);
  stats.maxSamples = max(stats.maxSamples, a.n);
}

void main() {
  // HT_ACCUM_SHOW_TARGETS_PER_INVOCATION consecutive targets per invocation (lavapipe pays much per invocation and
  // per subgroup operation; showing a target is a few loads and stores), dispatched in slices: pc.batchFirst is the
  // slice's first target, pc.batchCount its targets.
  uint first = HT_ACCUM_SHOW_TARGETS_PER_INVOCATION * gl_GlobalInvocationID.x;
  ShowStats stats = ShowStats(0u, 0u, 0xffffffffu, 0u);
  for (uint k = 0u; k < HT_ACCUM_SHOW_TARGETS_PER_INVOCATION; ++k) {
    if (first + k < pc.batchCount) show_target(pc.batchFirst + first + k, stats);
  }
  // Reduced per subgroup first: one atomic of each kind per subgroup, not per target (lavapipe runs atomics lane by
  // lane). The statistics are order-free (sum, min, max), so the result does not depend on the schedule.
  uint unconverged = subgroupAdd(stats.unconverged);
  uint maxErrorBits = subgroupMax(stats.maxErrorBits);
  uint minSamples = subgroupMin(stats.minSamples);
  uint maxSamples = subgroupMax(stats.maxSamples);
  if (subgroupElect()) {
    AccumStatsRef accumStats = AccumStatsRef(FRAME.accumStats);
    if (unconverged > 0u) atomicAdd(accumStats.s.unconverged, unconverged);
    atomicMax(accumStats.s.maxErrorBits, maxErrorBits);
    if (minSamples != 0xffffffffu) atomicMin(accumStats.s.minSamples, minSamples);
    atomicMax(accumStats.s.maxSamples, maxSamples);
  }
}
