#version 450
// glsl_compile_check.comp - build-time check that the shared camera headers compile as GLSL (Vulkan 1.2,
// glslangValidator with GL_GOOGLE_include_directive), exactly as the GPU raygen kernel includes them.
#extension GL_GOOGLE_include_directive : require
#include "camera_models/lenticular_model.h"
#include "camera_models/pinhole_model.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Params {
  LenticularParams lenticular;
  PinholeParams pinhole;
};
layout(std430, binding = 1) writeonly buffer Rays { vec4 rays[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint x = i % 1536u, y = i / 1536u;
  vec2 xi = vec2(0.5, 0.5);
  vec3 origin, dir;
  float t = lenticular_view_phase(lenticular, x, y, i % 3u, xi);
  lenticular_ray(lenticular, x, y, i % 3u, xi, origin, dir);
  rays[3u * i] = vec4(origin, t);
  rays[3u * i + 1u] = vec4(dir, 0.0);
  pinhole_ray(pinhole, x, y, xi, origin, dir);
  rays[3u * i + 2u] = vec4(dir, origin.x);
}
