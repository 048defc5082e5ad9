// accumulation_error.h - the per-target error estimate and stop rule of progressive accumulation (C++ and GLSL,
// one source; docs/REUSE.md §2).
//
// After Cycles' adaptive sampling (blender intern/cycles/kernel/film/adaptive_sampling.h) and Dammertz, Hanika,
// Keller & Lensch, "A hierarchical automatic stopping condition for Monte Carlo global illumination" (WSCG 2009):
// besides the sum of all n samples a target keeps the sum over the "odd half" of its samples (sample indices i with
// an odd popcount of i & 0xaaaaaaaa: half of every aligned group of 4). Both are unbiased estimates of the same
// value, so their difference measures the noise left:
//   error = sum over the shown channels |I - A| / (1e-4 + (L < 1 ? sqrt(L) : L))
// with I = sum / n, A = half sum / half count and L the mean of I over the shown channels (a subpixel target shows
// one channel, a pixel target three). The decision is a pure function of the stored sums and counts, so a replay of
// the same samples decides the same (bit-exactness, docs/REUSE.md §1).
#ifndef HT_ACCUMULATION_ERROR_H
#define HT_ACCUMULATION_ERROR_H
#include "common/glsl_cpp.h"
#include "common/exact_division.h"

HT_SHARED_BEGIN

// Whether sample index i belongs to the half estimate.
HT_INLINE bool ht_accum_in_half(uint i) {
#ifdef HT_GLSL
  return (bitCount(i & 0xaaaaaaaau) & 1) != 0;
#else
  return (__builtin_popcount(i & 0xaaaaaaaau) & 1) != 0;
#endif
}

HT_CONST float HT_ACCUM_UNKNOWN_ERROR = 3.0e38f;
// Targets one invocation of the show pass (accum_show.comp) shows.
HT_CONST uint HT_ACCUM_SHOW_TARGETS_PER_INVOCATION = 4u;

// Error estimate of a target from its means; `mask` is 1 for each channel the target shows, 0 otherwise. A target
// without half samples yet (n < 3) reports HT_ACCUM_UNKNOWN_ERROR: it cannot be judged.
HT_INLINE float ht_accum_error(vec3 mean, vec3 halfMean, uint halfCount, vec3 mask) {
  if (halfCount == 0u) return HT_ACCUM_UNKNOWN_ERROR;
  vec3 d = abs(mean - halfMean) * mask;
  float channels = mask.x + mask.y + mask.z;
  float l = max(ht_div(mean.x * mask.x + mean.y * mask.y + mean.z * mask.z, channels), 0.0f);
  return ht_div(d.x + d.y + d.z, 1e-4f + (l < 1.0f ? ht_sqrt(l) : l));
}

// The stop rule per target: it needs more samples below minSpp, and up to maxSpp while its error is not below the
// target error (a NaN error never counts as converged).
HT_INLINE bool ht_accum_needs_samples(uint n, float error, uint minSpp, uint maxSpp, float targetError) {
  if (n >= maxSpp) return false;
  return n < minSpp || !(error < targetError);
}

HT_SHARED_END
#endif
