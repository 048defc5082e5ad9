#version 460
#extension GL_GOOGLE_include_directive : require
// resolve: box-filters the spp samples of each target of the batch into the subpixel buffer.
// Subpixel targets (lenticular, integral) keep their own channel only (a subpixel shows one primary); pixel
// targets keep RGB.
#include "gpu/shaders/common.glsl"

layout(constant_id = 0) const uint MODEL = HT_MODEL_LENTICULAR;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint spp = FRAME.dims.z;
  if (i >= pc.batchCount / spp) return;
  uint entry = pc.batchFirst / spp + i;
  uint target = FRAME.refineInfo.w == 1u ? UintRef(FRAME.refine).v[FRAME.refineInfo.y + entry] : entry;  // refining: listed
  vec3 sum = vec3(0.0f);
  for (uint s = 0u; s < spp; ++s) sum += imageLoad(radianceBuffer, int(i * spp + s)).xyz;
  vec3 value = sum / float(spp);
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
