#version 460
#extension GL_GOOGLE_include_directive : require
// resolve: box-filters the spp samples of each target of the batch into the subpixel buffer.
// Subpixel targets (lenticular, integral) keep their own channel only (a subpixel shows one primary); pixel
// targets keep RGB. Refining (FRAME.refineInfo.w = the base pass's spp B != 0), a listed target's value becomes the
// mean of all its B + spp samples: (B x its base value + the sum of the new ones) / (B + spp). Dropping the base
// samples, as this pass first did, wasted a fifth of a 1 + 4 target's samples (Portrait, 1 + 4 at contrast 0.10:
// 49.70 -> 50.08 dB for one more texel load per refined target, docs/BENCHMARKS.md).
#include "gpu/shaders/common.glsl"
#include "gpu/accumulation_error.h"

layout(constant_id = HT_SPEC_MODEL) const uint MODEL = HT_MODEL_LENTICULAR;
// The refinement pass's pipeline: lavapipe would run the list and base-value loads of a runtime branch on every pass.
layout(constant_id = 1) const bool REFINING = false;
// Progressive accumulation (gpu/accumulator.h, docs/REUSE.md §1): the samples are added, in sample order, to the
// target's stored sums (AccumTarget), continuing from them, so k frames of N samples make the float additions of one
// frame of k*N; accum_show.comp then shows sum / n. Refining here means the listed targets of the adaptive policy.
layout(constant_id = 2) const bool PROGRESSIVE = false;
// A partial re-render over a bounce cache with links (ReusePlan::bounceLinks): once its listed target is done, the
// first bounce link of each of its paths is cleared, since the cached entries of a re-traced path may no longer be
// current (FrameReuseState::bounceFirst).
layout(constant_id = 3) const bool CLEAR_BOUNCE_LINKS = false;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint spp = FRAME.dims.z;
  if (i >= pc.batchCount / spp) return;
  uint entry = pc.batchFirst / spp + i;
  uint target = REFINING ? UintRef(FRAME.refine).v[FRAME.refineInfo.y + entry] : entry;  // refining: listed
  if (CLEAR_BOUNCE_LINKS) {
    for (uint s = 0u; s < spp; ++s) UintRef(FRAME.bounceFirst).v[target * spp + s] = HT_NO_BOUNCE;
  }
  if (PROGRESSIVE) {
    uint globalTarget = frame_global_target(target);
    AccumTarget a = load_accum_target(globalTarget);
    for (uint s = 0u; s < spp; ++s) {
      vec3 x = imageLoad(radianceBuffer, int(i * spp + s)).xyz;
      a.sum += x;
      if (ht_accum_in_half(a.n + s)) {
        a.halfSum += x;
        a.halfN += 1u;
      }
    }
    a.n += spp;
    store_accum_target(globalTarget, a);
    return;
  }
  vec3 sum = vec3(0.0f);
  for (uint s = 0u; s < spp; ++s) sum += imageLoad(radianceBuffer, int(i * spp + s)).xyz;
  vec3 value = ht_div3(sum, float(spp));
  uint baseSpp = FRAME.refineInfo.w;
  if (REFINING && baseSpp != 0u) {  // (a partial re-render lists targets with no base: their plain mean)
    bool subpixel = ht_model_has_subpixel_targets(MODEL);
    vec3 base = subpixel ? vec3(imageLoad(subpixelBuffer, int(target)).x)
                         : vec3(imageLoad(subpixelBuffer, int(3u * target)).x, imageLoad(subpixelBuffer, int(3u * target + 1u)).x,
                                imageLoad(subpixelBuffer, int(3u * target + 2u)).x);
    value = ht_div3(base * float(baseSpp) + sum, float(baseSpp + spp));
  }
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
}
