// accum_stats.glsl - the stop-rule statistics of progressive accumulation (AccumStats, gpu/wavefront_types.h;
// docs/REUSE.md §2): a target's error estimate and stop rule (gpu/accumulation_error.h) on its stored sums, folded
// per invocation and added per subgroup into an AccumStats by atomics. Included, after their MODEL specialization
// constant, by accum_show.comp (the targets a progressive frame shows) and refine_select.comp (the targets its
// selection leaves out for good).
#ifndef HT_ACCUM_STATS_GLSL
#define HT_ACCUM_STATS_GLSL
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu/accumulation_error.h"

// The statistics of some targets: how many need samples, their largest error (float bits) and their fewest and
// most samples.
struct TargetStats {
  uint unconverged, maxErrorBits, minSamples, maxSamples;
};

TargetStats no_target_stats() { return TargetStats(0u, 0u, 0xffffffffu, 0u); }

// The channels chunk target `target` shows: its own for a subpixel target, all three for a pixel target.
vec3 accum_shown_channels(uint target) {
  if (!ht_model_has_subpixel_targets(MODEL)) return vec3(1.0f);
  uint c = target % 3u;
  return vec3(c == 0u ? 1.0f : 0.0f, c == 1u ? 1.0f : 0.0f, c == 2u ? 1.0f : 0.0f);
}

// The value a target shows: the mean of its samples (0 before its first).
vec3 accum_mean(AccumTarget a) { return a.n > 0u ? ht_div3(a.sum, float(a.n)) : vec3(0.0f); }

// Its error estimate, from its mean and the mean of its half samples.
float accum_target_error(AccumTarget a, uint target) {
  vec3 halfMean = a.halfN > 0u ? ht_div3(a.halfSum, float(a.halfN)) : vec3(0.0f);
  return ht_accum_error(accum_mean(a), halfMean, a.halfN, accum_shown_channels(target));
}

// The stop rule of the frame's accumulation (FRAME.accum: target error, min spp, max spp).
bool accum_needs_samples(uint n, float error) {
  return ht_accum_needs_samples(n, error, FRAME.accum.z, FRAME.accum.w, uintBitsToFloat(FRAME.accum.y));
}

// Folds one target into `stats`.
void fold_target_stats(inout TargetStats stats, uint n, float error, bool needs) {
  stats.unconverged += needs ? 1u : 0u;
  stats.maxErrorBits = max(stats.maxErrorBits, isnan(error) ? 0u : floatBitsToUint(min(error, HT_ACCUM_UNKNOWN_ERROR)));
  stats.minSamples = min(stats.minSamples, n);
  stats.maxSamples = max(stats.maxSamples, n);
}

// Adds every invocation's `stats` to the AccumStats at `address`: reduced per subgroup first, one atomic of each
// kind per subgroup (lavapipe runs atomics lane by lane). Sum, min and max are order-free, so the result does not
// depend on the schedule. Call in uniform control flow.
void add_target_stats(TargetStats stats, uint64_t address) {
  uint unconverged = subgroupAdd(stats.unconverged);
  uint maxErrorBits = subgroupMax(stats.maxErrorBits);
  uint minSamples = subgroupMin(stats.minSamples);
  uint maxSamples = subgroupMax(stats.maxSamples);
  if (subgroupElect()) {
    AccumStatsRef accumStats = AccumStatsRef(address);
    if (unconverged > 0u) atomicAdd(accumStats.s.unconverged, unconverged);
    if (maxErrorBits > 0u) atomicMax(accumStats.s.maxErrorBits, maxErrorBits);
    if (minSamples != 0xffffffffu) atomicMin(accumStats.s.minSamples, minSamples);
    if (maxSamples > 0u) atomicMax(accumStats.s.maxSamples, maxSamples);
  }
}

#endif
