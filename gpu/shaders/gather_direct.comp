#version 460
#extension GL_GOOGLE_include_directive : require
// gather_direct: adds the unoccluded direct-light contributions of each path shaded at this depth, light by
// light in a fixed order, so the sum (and the frame) is bit-identical from run to run whatever order the
// shadow queue was filled in.
#include "gpu/shaders/common.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= COUNTERS.queueCount[pc.queue]) return;
  uint path = queue_path(i);
  uint lightCount = FRAME.scene.x;
  vec3 sum = vec3(0.0f);
  for (uint l = 0u; l < lightCount; ++l) {
    uint slot = path * lightCount + l;
    vec4 c = imageLoad(shadowContribBuffer, int(slot));
    if (c.w != 0.0f) {
      sum += c.xyz;
      imageStore(shadowContribBuffer, int(slot), vec4(0.0f));
    }
  }
  imageStore(radianceBuffer, int(path), imageLoad(radianceBuffer, int(path)) + vec4(sum, 0.0f));
}
