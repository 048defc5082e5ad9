#version 460
// exact_math_probe.comp - runs the shared ht_div, ht_div3 and ht_sqrt (common/exact_division.h) on the GPU for a list
// of inputs, so tests can compare them bit for bit with C++'s `/` and std::sqrt (gpu/kernel_probe.h,
// tests/gpu/exact_math_probe_test.cpp). Buffers are addressed through push-constant device addresses.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

layout(local_size_x = 64) in;

#include "common/exact_division.h"

// Input i: (a, b, x, unused); output i: (ht_div(a, b), ht_sqrt(x), ht_div3(vec3(a, x, b), b).y, 0).
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
  vec4 in4 = ProbeInput(probe.inputAddress).v[i];
  ProbeOutput(probe.outputAddress).v[i] =
      vec4(ht_div(in4.x, in4.y), ht_sqrt(in4.z), ht_div3(vec3(in4.x, in4.z, in4.y), in4.y).y, 0.0f);
}
