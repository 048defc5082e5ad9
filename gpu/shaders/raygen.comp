#version 460
#extension GL_GOOGLE_include_directive : require
// raygen: one invocation per path (target x sample). Writes the primary ray of the path into ray queue 0
// and initialises its radiance and throughput. Targets are subpixels (lenticular: target = 3*(y*W + x) + c)
// or pixels (pinhole: target = y*W + x), y counted from the bottom (optics.md §0).
#include "gpu/shaders/common.glsl"
#include "camera_models/lenticular_model.h"
#include "camera_models/pinhole_model.h"

layout(constant_id = 0) const uint MODEL = HT_MODEL_LENTICULAR;

// Sample s of the target's footprint. One sample: the footprint centre, i.e. exactly the vendor's sample point.
// More: the R2 low-discrepancy sequence (Roberts 2018, generalised golden ratio g: g^3 = g + 1) with a
// per-target Cranley-Patterson rotation, so neighbouring subpixels are decorrelated.
vec2 footprint_sample(uint target, uint s, uint spp, uint seed) {
  if (spp == 1u) return vec2(0.5f);
  const float g = 1.32471795724474602596f;
  const vec2 alpha = vec2(1.0f / g, 1.0f / (g * g));
  uint h = ht_hash(target * 0x9E3779B9u ^ ht_hash(seed));
  vec2 shift = vec2(ht_uint_to_unit(h), ht_uint_to_unit(ht_hash(h)));
  return fract(shift + alpha * float(s));
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i == 0u) {
    COUNTERS.queueCount[0] = pc.batchCount;
    COUNTERS.queueCount[1] = 0u;
    COUNTERS.shadowCount = 0u;
  }
  if (i >= pc.batchCount) return;
  uint spp = FRAME.dims.z;
  uint width = FRAME.dims.x;
  uint path = pc.batchFirst + i;
  uint target = path / spp;
  vec2 xi = footprint_sample(target, path % spp, spp, FRAME.frame.x);
  vec3 origin;
  vec3 dir;
  if (MODEL == HT_MODEL_LENTICULAR) {
    uint pixel = target / 3u;
    lenticular_ray(FRAME.lenticular, pixel % width, pixel / width, target % 3u, xi, origin, dir);
  } else {
    pinhole_ray(FRAME.pinhole, target % width, target / width, xi, origin, dir);
  }
  store_ray(0u, i, HtRay(origin, 0.0f, dir, 3.0e38f));
  store_queue_path(0u, i, i);
  imageStore(radianceBuffer, int(i), vec4(0.0f));
  imageStore(throughputBuffer, int(i), vec4(1.0f));
}
