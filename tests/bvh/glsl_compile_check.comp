#version 460
// glsl_compile_check.comp - build-time check that the shared bvh headers compile as GLSL and that every
// shared function can be called from a Vulkan compute shader. Buffers are read through buffer_reference
// blocks whose addresses sit in push constants, the way the GPU kernels are expected to bind them.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

layout(local_size_x = 64) in;

#include "bvh/ray_types.h"
#include "bvh/gpu_node.h"

layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer NodeBuffer { GpuBvhNode nodes[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer TriangleBuffer { vec4 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer RayBuffer { HtRay rays[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) writeonly buffer HitBuffer { HtHit hits[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) writeonly buffer Vec4Buffer { vec4 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer InstanceBuffer { uvec4 v[]; };

layout(push_constant, scalar) uniform Push {
  NodeBuffer nodes;
  TriangleBuffer triangles;
  RayBuffer rays;
  HitBuffer hits;
  Vec4Buffer extra;
  NodeBuffer topNodes;
  InstanceBuffer instances;
  uint rayCount;
  uint stepLimit;
} pc;

#define HT_LOAD_NODE(i) pc.nodes.nodes[i]
#define HT_LOAD_TRI(i) pc.triangles.v[i]
#include "bvh/bvh_traversal.h"
#include "bvh/offset_ray.h"
#define HT_LOAD_TOP_NODE(i) pc.topNodes.nodes[i]
#define HT_LOAD_INSTANCE(i) pc.instances.v[i]
#include "bvh/ordered_traversal.h"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.rayCount) return;
  HtRay ray = pc.rays.rays[i];

  HtTraceResult closest = ht_trace_closest(ray, pc.stepLimit);
  HtTraceResult any = ht_trace_any(ray, pc.stepLimit);
  HtTraceResult ordered = ht_trace_closest_ordered(ray, pc.stepLimit);
  HtTraceResult twoLevel = ht_trace_two_level_ordered(ray, pc.stepLimit);
  pc.hits.hits[2u * i] = closest.hit;
  pc.hits.hits[2u * i + 1u] = any.hit;

  // Direct calls of the building blocks.
  HtSlabRay slabRay = ht_make_slab_ray(ray.origin, ray.dir, ray.tmin);
  bool hit0;
  bool hit1;
  float t0;
  float t1;
  ht_slab_node(slabRay, HT_LOAD_NODE(0u), ray.tmax, hit0, hit1, t0, t1);
  HtWatertightRay triRay = ht_make_watertight_ray(ray.origin, ray.dir, ray.tmin);
  float t;
  float u;
  float v;
  bool triHit = ht_intersect_triangle(triRay, vec3(HT_LOAD_TRI(0u)), vec3(HT_LOAD_TRI(1u)), vec3(HT_LOAD_TRI(2u)),
                                      ray.tmax, t, u, v);
  vec3 offset = ht_offset_ray(ray.origin, ray.dir);
  float flags = float(hit0) + 2.0f * float(hit1) + 4.0f * float(triHit) + 8.0f * float(closest.overflow) +
                16.0f * float(ht_ray_is_valid(ray)) + ht_safe_rcp(ray.dir.x) + ht_min_nan(t0, t1) +
                ht_max_nan(u, v) + float(closest.steps + any.steps) +
                ordered.hit.t + twoLevel.hit.t;
  pc.extra.v[i] = vec4(offset, flags + t);
}
