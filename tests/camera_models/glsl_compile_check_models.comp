#version 450
// glsl_compile_check_models.comp - build-time check that the issue-3 camera headers (quilt, projector, integral,
// lens distortion, capture grid, oblique, ray table) compile
// as GLSL (Vulkan 1.2, glslangValidator with GL_GOOGLE_include_directive), as the raygen kernel will include them.
#extension GL_GOOGLE_include_directive : require
#include "camera_models/quilt_model.h"
#include "camera_models/projector_model.h"
#include "camera_models/integral_model.h"
#include "camera_models/lens_distortion.h"
#include "camera_models/pinhole_model.h"
#include "camera_models/capture_grid_model.h"
#include "camera_models/oblique_model.h"

// The ray table is read through texel buffers, as the raygen kernel is expected to bind it.
layout(binding = 2) uniform samplerBuffer rayTableOrigins;
layout(binding = 3) uniform samplerBuffer rayTableDirections;
#define HT_RAY_TABLE_ORIGIN(i) texelFetch(rayTableOrigins, int(i)).xyz
#define HT_RAY_TABLE_DIRECTION(i) texelFetch(rayTableDirections, int(i)).xyz
#include "camera_models/ray_table_model.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Params {
  QuiltParams quilt;
  ProjectorArrayParams projectors;
  IntegralParams integral;
  PinholeParams pinhole;
  CaptureGridParams captureGrid;
  ObliqueParams oblique;
  RayTableParams rayTable;
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
  pinhole_ray(pinhole, x, y, xi, origin, dir);
  rays[4u * i + 1u] += vec4(dir, origin.y);
  capture_grid_ray(captureGrid, x, y, i % 48u, xi, origin, dir);
  rays[4u * i + 2u] += vec4(dir, origin.z);
  oblique_ray(oblique, x, y, i % 81u, xi, origin, dir);
  rays[4u * i + 3u] += vec4(dir, origin.x);
  ray_table_ray(rayTable, x, y, vec2(0.25, 0.75), origin, dir);
  rays[4u * i] += vec4(origin + dir, 1.0);
}
