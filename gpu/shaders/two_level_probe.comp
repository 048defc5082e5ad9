#version 460
// two_level_probe.comp - runs the shared order-free two-level traversal (bvh/ordered_traversal.h) on the GPU for a
// list of rays, so tests can compare its hits bit for bit with the C++ build of the same header (gpu/kernel_probe.h,
// tests/gpu/gpu_two_level_test.cpp). Buffers are addressed through push-constant device addresses.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

layout(local_size_x = 64) in;

#include "bvh/ray_types.h"
#include "bvh/gpu_node.h"

layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer NodeBuffer { GpuBvhNode v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer Vec4Buffer { vec4 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer InstanceBuffer { uvec4 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer RayBuffer { HtRay v[]; };
// Output i: (t bits, triangle id, u bits, v bits) and (steps, overflow, 0, 0).
layout(buffer_reference, scalar, buffer_reference_align = 16) writeonly buffer OutputBuffer { uvec4 v[]; };

layout(push_constant, scalar) uniform ProbeConstants {
  uint64_t topNodes;
  uint64_t instances;
  uint64_t blasNodes;
  uint64_t triangles;
  uint64_t rays;
  uint64_t outputs;
  uint count;
  uint stepLimit;
} probe;

#define HT_LOAD_NODE(i) NodeBuffer(probe.blasNodes).v[i]
#define HT_LOAD_TRI(i) Vec4Buffer(probe.triangles).v[i]
#define HT_LOAD_TOP_NODE(i) NodeBuffer(probe.topNodes).v[i]
#define HT_LOAD_INSTANCE(i) InstanceBuffer(probe.instances).v[i]
#include "bvh/ordered_traversal.h"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= probe.count) return;
  HtRay ray = RayBuffer(probe.rays).v[i];
  HtTraceResult r = ht_trace_two_level_ordered(ray, probe.stepLimit);
  OutputBuffer out_ = OutputBuffer(probe.outputs);
  out_.v[2u * i] = uvec4(floatBitsToUint(r.hit.t), r.hit.triId, floatBitsToUint(r.hit.u), floatBitsToUint(r.hit.v));
  out_.v[2u * i + 1u] = uvec4(r.steps, r.overflow ? 1u : 0u, 0u, 0u);
}
