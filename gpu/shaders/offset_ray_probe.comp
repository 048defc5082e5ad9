#version 460
// offset_ray_probe.comp - runs the shared ht_offset_ray (bvh/offset_ray.h) on the GPU for a list of (p, n) pairs, so
// tests can compare its result bit for bit with the C++ build of the same header (gpu/kernel_probe.h,
// tests/accuracy/offset_ray_glsl_test.cpp). Buffers are addressed through push-constant device addresses.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

layout(local_size_x = 64) in;

#include "bvh/offset_ray.h"

// Input pair i: p = v[2i].xyz, n = v[2i+1].xyz; output i: offset origin in .xyz (w = 0).
layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer ProbeInput { vec4 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) writeonly buffer ProbeOutput { vec4 v[]; };

layout(push_constant, scalar) uniform ProbeConstants {
  uint64_t inputAddress;
  uint64_t outputAddress;
  uint count;
} probe;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= probe.count) return;
  ProbeInput inputs = ProbeInput(probe.inputAddress);
  ProbeOutput outputs = ProbeOutput(probe.outputAddress);
  vec3 p = inputs.v[2u * i].xyz;
  vec3 n = inputs.v[2u * i + 1u].xyz;
  outputs.v[i] = vec4(ht_offset_ray(p, n), 0.0f);
}
