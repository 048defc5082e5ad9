// footprint_sampling.h - where the samples of one pixel / subpixel footprint go (shared C++/GLSL, so a test can
// regenerate on the CPU exactly the footprint positions the GPU raygen used).
//
// Every camera model maps a footprint position xi to a ray: xi in [0,1)^2 covers the pixel / subpixel (the box
// filter's support); the models are affine in xi, so xi outside [0,1) reaches into the neighbours, which wider filters
// need. The renderer averages its samples with equal weights, so the reconstruction filter is applied by *importance
// sampling* it (filter importance sampling: Ernst, Stamminger, Greiner, "Filter Importance Sampling", IEEE RT 2006;
// pbrt-v4 §8.8 FilterSampler): the stratified points are warped through the filter's inverse CDF.
//   box:      xi unchanged, support [0, 1)
//   tent:     radius 1 footprint (support [-0.5, 1.5)), inverse CDF of the triangle per axis
//   Gaussian: sigma 0.5 footprint per axis (Box-Muller), untruncated; 99.7 % within [-1, 2)
// For the lenticular model the footprint is the subpixel, whose x extent is its width in view phase, so a wide
// filter prefilters across views (docs/OPTICS.md §8 item 4; Zwicker et al. 2006) instead of snapping to them.
//
// Points: the R2 low-discrepancy sequence (Roberts 2018, "The unreasonable effectiveness of quasirandom sequences":
// alpha = (1/g, 1/g^2), g^3 = g + 1) with a per-target Cranley-Patterson rotation (Cranley & Patterson 1976) so
// neighbouring targets are decorrelated; the projector model's angular scattering draws its second pair from dimensions
// 3-4 of the R4 sequence (g^5 = g + 1) with its own shift, a lattice independent of the position pair's. One sample =
// the footprint centre exactly.
#ifndef HT_FOOTPRINT_SAMPLING_H
#define HT_FOOTPRINT_SAMPLING_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

HT_CONST uint HT_FILTER_BOX = 0u;
HT_CONST uint HT_FILTER_TENT = 1u;
HT_CONST uint HT_FILTER_GAUSSIAN = 2u;
HT_CONST float HT_FOOTPRINT_TWO_PI = 6.28318530717958647692f;

// Integer hash (PCG-style output permutation; Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020).
HT_INLINE uint ht_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

HT_INLINE float ht_uint_to_unit(uint v) { return float(v >> 8u) * (1.0f / 16777216.0f); }  // [0,1), 24 bits

// Cranley-Patterson shift of `target` for stream `stream` (0: position, 1: angle).
HT_INLINE vec2 footprint_shift(uint target, uint seed, uint stream) {
  uint h = ht_hash(target * 0x9E3779B9u ^ ht_hash(seed + stream * 0x68E31DA4u));
  return vec2(ht_uint_to_unit(h), ht_uint_to_unit(ht_hash(h)));
}

// Point s of a rank-1 lattice with generator alpha (32-bit fixed point): fract(s * alpha) computed exactly as the
// wrapping product s * alpha mod 2^32, so the stratification holds for every spp (a float product would lose
// log2(s) bits of the fraction).
HT_INLINE vec2 footprint_lattice(uint s, uvec2 alphaFixed) {
  uvec2 f = alphaFixed * s;
  return vec2(ht_uint_to_unit(f.x), ht_uint_to_unit(f.y));
}

// Tent filter of radius 1 around the footprint centre, per axis: inverse CDF of the triangle on [-1, 1] (pbrt-v4
// SampleTent), then shifted so the centre sits at 0.5.
HT_INLINE float footprint_tent(float u) {
  float t = u < 0.5f ? sqrt(2.0f * u) - 1.0f : 1.0f - sqrt(2.0f - 2.0f * u);
  return 0.5f + t;
}

// Gaussian filter, sigma 0.5 footprint per axis, from a uniform pair (Box-Muller).
HT_INLINE vec2 footprint_gaussian(vec2 u) {
  float r = 0.5f * sqrt(-2.0f * log(max(1.0f - u.x, 1e-30f)));
  float a = HT_FOOTPRINT_TWO_PI * u.y;
  return vec2(0.5f + r * cos(a), 0.5f + r * sin(a));
}

HT_INLINE vec2 footprint_warp(vec2 u, uint filterKind) {
  if (filterKind == HT_FILTER_TENT) return vec2(footprint_tent(u.x), footprint_tent(u.y));
  if (filterKind == HT_FILTER_GAUSSIAN) return footprint_gaussian(u);
  return u;
}

// Footprint position of sample s (of spp) of `target`.
HT_INLINE vec2 footprint_sample(uint target, uint s, uint spp, uint seed, uint filterKind) {
  if (spp == 1u) return vec2(0.5f);
  // (1/g, 1/g^2) * 2^32 with g = 1.32471795724474602596 (plastic number, g^3 = g + 1). Two R2 points lie 0.245
  // apart in x (mod 1), so spp 2 uses the 2-point rank-1 lattice (1/2, 1/2) instead: one sample in each half of the
  // footprint on both axes (for a lenticular subpixel, each half of its view-phase width).
  uvec2 alpha = spp == 2u ? uvec2(0x80000000u, 0x80000000u) : uvec2(0xC13FA9A9u, 0x91E10DA6u);
  vec2 u = fract(footprint_shift(target, seed, 0u) + footprint_lattice(s, alpha));
  return footprint_warp(u, filterKind);
}

// Footprint position of sample index i of `target` in a progressive accumulation (docs/REUSE.md §1, §6 item 1):
// always the R2 lattice point i, whatever the frame's spp, so the samples of k frames of N continue one sequence and
// equal those of one frame of k*N (for spp >= 3 also the points footprint_sample gives a single frame).
HT_INLINE vec2 footprint_sample_progressive(uint target, uint i, uint seed, uint filterKind) {
  return footprint_sample(target, i, 3u, seed, filterKind);
}

// Second footprint pair of sample s: dimensions 3 and 4 of the R4 sequence (g^5 = g + 1), for angular footprints
// (projector scattering). Uniform in [0,1)^2; the model applies its own angular distribution.
HT_INLINE vec2 footprint_sample_angle(uint target, uint s, uint spp, uint seed) {
  if (spp == 1u) return vec2(0.5f);
  // (1/g^3, 1/g^4) * 2^32 with g = 1.16730397826141868426 (g^5 = g + 1)
  return fract(footprint_shift(target, seed, 1u) + footprint_lattice(s, uvec2(0xA0F2EC76u, 0x89E18285u)));
}

HT_SHARED_END
#endif  // HT_FOOTPRINT_SAMPLING_H
