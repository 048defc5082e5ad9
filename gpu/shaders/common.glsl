// common.glsl - included first by every holotrace compute pass: extensions, buffer-reference types over the
// shared layouts (gpu/wavefront_types.h), push constants and small helpers.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference2 : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "gpu/wavefront_types.h"
#include "bvh/ray_types.h"
#include "bvh/gpu_node.h"

layout(local_size_x = HT_WORKGROUP_SIZE) in;

layout(buffer_reference, std430, buffer_reference_align = 16) buffer FrameRef { FrameBlock f; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer NodeRef { GpuBvhNode n[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Vec4Ref { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Vec2Ref { vec2 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer UVec4Ref { uvec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer UintRef { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer FloatRef { float v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer RayRef { HtRay v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer HitRef { HtHit v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer MaterialRef { GpuMaterial v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer LightRef { GpuLight v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TextureRef { GpuTexture v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer CountersRef { GpuCounters c; };

layout(push_constant, std430) uniform PushBlock { PassConstants pc; };

#define FRAME FrameRef(pc.frame).f
#define COUNTERS CountersRef(FrameRef(pc.frame).f.counters).c

// Integer hash (PCG-style output permutation; Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020).
uint ht_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

float ht_uint_to_unit(uint v) { return float(v >> 8) * (1.0f / 16777216.0f); }  // [0,1), 24 bits
