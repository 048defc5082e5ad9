#version 450
// glsl_compile_check_models.comp - build-time check that the issue-3 camera headers (quilt, projector, integral,
// lens distortion, capture grid) compile
// as GLSL (Vulkan 1.2, glslangValidator with GL_GOOGLE_include_directive), as the raygen kernel will include them.
#extension GL_GOOGLE_include_directive : require
#include "camera_models/quilt_model.h"
#include "camera_models/projector_model.h"
#include "camera_models/integral_model.h"
#include "camera_models/lens_distortion.h"
#include "camera_models/capture_grid_model.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Params {
  QuiltParams quilt;
  ProjectorArrayParams projectors;
  IntegralParams integral;
  PinholeParams pinhole;
  LensDistortion distortion;
  CaptureGridParams captureGrid;
};
layout(std430, binding = 1) writeonly buffer Rays { vec4 rays[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint x = i % 1024u, y = i / 1024u;
  vec2 xi = vec2(0.5, 0.5);
  vec3 origin, dir;
  quilt_ray(quilt, x, y, i % 48u, xi, origin, dir);
  rays[4u * i] = vec4(origin, 0.0);
  rays[4u * i + 1u] = vec4(dir, 0.0);
  projector_ray(projectors, x, y, i % 70u, xi, origin, dir);
  rays[4u * i + 2u] = vec4(origin, dir.x);
  projector_scattered_ray(projectors, x, y, i % 70u, xi, vec2(0.3, 0.7), origin, dir);
  rays[4u * i + 3u] = vec4(dir, origin.x);
  integral_ray(integral, x, y, 0u, xi, origin, dir);
  rays[4u * i] += vec4(origin, dir.z);
  pinhole_distorted_ray(pinhole, distortion, x, y, xi, origin, dir);
  rays[4u * i + 1u] += vec4(dir, origin.y);
  capture_grid_ray(captureGrid, x, y, i % 48u, xi, origin, dir);
  rays[4u * i + 2u] += vec4(dir, origin.z);
}
