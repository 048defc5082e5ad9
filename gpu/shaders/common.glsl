// common.glsl - included first by every holotrace compute pass: extensions, the resources of descriptor set 0,
// accessors over them, push constants and small helpers.
//
// Why texel buffers: Mesa 22.3's lavapipe expands each 32-bit component of a storage-buffer or device-address
// load/store into a loop over the 8 SIMD lanes (gallivm lp_bld_nir_soa.c emit_load_global / emit_load_mem), while
// image and texel-buffer accesses handle all lanes at once. Per-path state therefore lives in storage texel
// buffers, read-only scene records in uniform texel buffers, the frame parameters in a uniform buffer (uniform
// loads are scalar). Device addresses reach the atomic queue counters and what the frame-reuse and accumulation
// passes write; the marking and partial re-render passes read the reuse caches back through uniform texel views of
// the same buffers (HT_BINDING_REUSE_*). GPUs are indifferent.
// Binding numbers and shared specialisation ids: gpu/shader_interface.h.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference2 : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "gpu/wavefront_types.h"
#include "bvh/ray_types.h"
#include "bvh/gpu_node.h"

layout(local_size_x = HT_WORKGROUP_SIZE) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer NodeRef { GpuBvhNode n[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Vec4Ref { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer CountersRef { GpuCounters c; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer UintRef { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer AccumStatsRef { AccumStats s; };

layout(push_constant, std430) uniform PushBlock { PassConstants pc; };

layout(set = 0, binding = HT_BINDING_FRAME, std140) uniform FrameUniforms { FrameBlock frameBlock; };
#define FRAME frameBlock
#define COUNTERS CountersRef(frameBlock.counters).c

// Per-path state (storage texel buffers).
layout(set = 0, binding = HT_BINDING_RAY_QUEUE_0, rgba32f) uniform imageBuffer rayQueue0;         // 2 texels per ray
layout(set = 0, binding = HT_BINDING_RAY_QUEUE_1, rgba32f) uniform imageBuffer rayQueue1;
layout(set = 0, binding = HT_BINDING_QUEUE_PATH_0, r32ui) uniform uimageBuffer queuePath0;
layout(set = 0, binding = HT_BINDING_QUEUE_PATH_1, r32ui) uniform uimageBuffer queuePath1;
layout(set = 0, binding = HT_BINDING_QUEUE_LEAVES, r32ui) uniform uimageBuffer queueLeaves;  // both queues'
layout(set = 0, binding = HT_BINDING_HITS, rgba32ui) uniform uimageBuffer hitBuffer;        // t bits, triId, u bits, v bits
layout(set = 0, binding = HT_BINDING_RADIANCE, rgba32f) uniform imageBuffer radianceBuffer;
layout(set = 0, binding = HT_BINDING_THROUGHPUT, rgba32f) uniform imageBuffer throughputBuffer;
layout(set = 0, binding = HT_BINDING_SHADOW_RAYS, rgba32f) uniform imageBuffer shadowRayBuffer;   // 2 texels per slot
layout(set = 0, binding = HT_BINDING_SHADOW_CONTRIB, rgba32f) uniform imageBuffer shadowContribBuffer;
layout(set = 0, binding = HT_BINDING_SHADOW_QUEUE, rg32ui) uniform uimageBuffer shadowQueueBuffer;
layout(set = 0, binding = HT_BINDING_SUBPIXELS, r32f) uniform imageBuffer subpixelBuffer;
layout(set = 0, binding = HT_BINDING_OUTPUT_IMAGE, rgba32f) uniform imageBuffer outputImage;
// Scene records (uniform texel buffers).
layout(set = 0, binding = HT_BINDING_VERTICES) uniform samplerBuffer vertexTexels;
layout(set = 0, binding = HT_BINDING_NORMALS) uniform samplerBuffer normalTexels;
layout(set = 0, binding = HT_BINDING_TEXCOORDS) uniform samplerBuffer texcoordTexels;           // RG32F
layout(set = 0, binding = HT_BINDING_TRIANGLES) uniform usamplerBuffer triangleTexels;          // (i0, i1, i2, material)
layout(set = 0, binding = HT_BINDING_MATERIALS) uniform samplerBuffer materialTexels;           // 3 texels per GpuMaterial
layout(set = 0, binding = HT_BINDING_LIGHTS) uniform samplerBuffer lightTexels;              // 4 texels per GpuLight
layout(set = 0, binding = HT_BINDING_TEXTURES) uniform usamplerBuffer textureTexels;           // GpuTexture.info
layout(set = 0, binding = HT_BINDING_TEXELS) uniform samplerBuffer texelTexels;
layout(set = 0, binding = HT_BINDING_RAY_TABLE) uniform samplerBuffer rayTableTexels;           // 2 texels per entry: origin, direction
layout(set = 0, binding = HT_BINDING_SUBPIXEL_TEXELS) uniform samplerBuffer subpixelTexels;           // subpixelBuffer, read through texel fetches
// The frame-reuse state the marking and partial re-render passes read (uniform texel views whose writers reach the
// same buffers by device address; Renderer::Impl::bindReuseTexels).
layout(set = 0, binding = HT_BINDING_REUSE_MASKS) uniform usamplerBuffer reuseMaskTexels;              // 4 mask words per texel
layout(set = 0, binding = HT_BINDING_REUSE_PRIMARY_RAYS) uniform samplerBuffer reusePrimaryRayTexels;  // 2 texels per path
layout(set = 0, binding = HT_BINDING_REUSE_PRIMARY_HITS) uniform usamplerBuffer reusePrimaryHitTexels;
layout(set = 0, binding = HT_BINDING_REUSE_BOUNCES) uniform usamplerBuffer reuseBounceTexels;          // the bounce cache
// A progressive accumulation's sums, a texel per target of the whole frame in each (storage texel buffers).
layout(set = 0, binding = HT_BINDING_ACCUM_SUMS, rgba32ui) uniform uimageBuffer accumSums;      // sum bits, n
layout(set = 0, binding = HT_BINDING_ACCUM_HALVES, rgba32ui) uniform uimageBuffer accumHalves;  // halfSum bits, halfN

// The index of chunk target `target` in the whole frame: targets count pixels x, then rows y from the bottom, then
// views, FRAME.frame.z per pixel (raygen.comp). A chunk covers views [FRAME.views.y, + FRAME.views.x) and rows
// [FRAME.views.w, + FRAME.dims.y) of views FRAME.frame.y rows high. Sample positions and random choices are keyed by
// this index, never by the index within the chunk, so a chunk of views or a band of rows renders exactly the bits the
// whole frame has at those targets (RenderSettings::region, the cluster's work units).
uint frame_global_target(uint target) {
  uint perPixel = FRAME.frame.z;
  uint width = FRAME.dims.x;
  uint pixel = target / perPixel;
  uint bandPixels = width * FRAME.dims.y;
  uint y = FRAME.views.w + (pixel % bandPixels) / width;
  uint view = FRAME.views.y + pixel / bandPixels;
  return ((view * FRAME.frame.y + y) * width + pixel % width) * perPixel + target % perPixel;
}

// Progressive frames (FRAME.accum.x = 1, gpu/accumulator.h): the samples target `globalTarget` already has. Sample
// s of this frame is sample index n + s of the target's sequence (docs/REUSE.md §1 rule 1).
uint accum_samples_so_far(uint globalTarget) { return imageLoad(accumSums, int(globalTarget)).w; }
// Target `globalTarget`'s sums (AccumTarget), kept in two planes of a texel per target (accumulator.h).
AccumTarget load_accum_target(uint globalTarget) {
  uvec4 s = imageLoad(accumSums, int(globalTarget)), h = imageLoad(accumHalves, int(globalTarget));
  return AccumTarget(uintBitsToFloat(s.xyz), s.w, uintBitsToFloat(h.xyz), h.w);
}
void store_accum_target(uint globalTarget, AccumTarget a) {
  imageStore(accumSums, int(globalTarget), uvec4(floatBitsToUint(a.sum), a.n));
  imageStore(accumHalves, int(globalTarget), uvec4(floatBitsToUint(a.halfSum), a.halfN));
}
// What an accumulation records of target `target`'s primary segments (docs/REUSE.md §4 in streams; an accumulation
// that records segments is one chunk covering the whole frame, so chunk and frame index agree), after the masks of
// all FRAME.dims.w targets (gpu/frame_reuse.h kMaskWords per target), a word per target each: its reach, the largest
// primary hit distance of its samples so far (a miss: its tmax), as float bits; the nearest and the farthest of its
// hits (the nearest as the complement of its bits, 0 while it has none). record_segments.comp raises them with
// atomicMax (t >= 0, so float bits order as unsigned integers); mark_accumulated.comp tests the samples' primary
// segments up to the reach and the shadow rays from their hits between the nearest and the farthest.
uint accum_reach_word(uint target) { return 4u * FRAME.dims.w + target; }
uint accum_near_hit_word(uint target) { return 5u * FRAME.dims.w + target; }
uint accum_far_hit_word(uint target) { return 6u * FRAME.dims.w + target; }

HtRay load_ray(uint q, uint i) {
  int k = int(2u * i);
  vec4 a = q == 0u ? imageLoad(rayQueue0, k) : imageLoad(rayQueue1, k);
  vec4 b = q == 0u ? imageLoad(rayQueue0, k + 1) : imageLoad(rayQueue1, k + 1);
  return HtRay(a.xyz, a.w, b.xyz, b.w);
}
void store_ray(uint q, uint i, HtRay r) {
  int k = int(2u * i);
  if (q == 0u) {
    imageStore(rayQueue0, k, vec4(r.origin, r.tmin));
    imageStore(rayQueue0, k + 1, vec4(r.dir, r.tmax));
  } else {
    imageStore(rayQueue1, k, vec4(r.origin, r.tmin));
    imageStore(rayQueue1, k + 1, vec4(r.dir, r.tmax));
  }
}
uint load_queue_path(uint q, uint i) {
  return q == 0u ? imageLoad(queuePath0, int(i)).x : imageLoad(queuePath1, int(i)).x;
}
// The convex part the ray in slot i of queue q leaves on its outside (0: none; gpu/convex_parts.h).
uint load_queue_leaves(uint q, uint i) { return imageLoad(queueLeaves, int(q * pc.batchCount + i)).x; }
void store_queue_leaves(uint q, uint i, uint part) { imageStore(queueLeaves, int(q * pc.batchCount + i), uvec4(part)); }
void store_queue_path(uint q, uint i, uint path) {
  if (q == 0u) imageStore(queuePath0, int(i), uvec4(path));
  else imageStore(queuePath1, int(i), uvec4(path));
}
// Depth 0 runs over the batch in raygen order -- entry i of queue 0 is path i, with radiance 0 and throughput 1 --
// so raygen writes none of those and the depth-0 pipelines (PRIMARY_DEPTH = true, set by the host for the dispatches
// at depth 0) read none: lavapipe stores and loads storage texels lane by lane, and these were 3 of raygen's 5
// stores. A specialisation constant rather than a test of pc.depth, which made shade slower on lavapipe (measured).
layout(constant_id = HT_SPEC_PRIMARY_DEPTH) const bool PRIMARY_DEPTH = false;
uint queue_path(uint i) {
  if (PRIMARY_DEPTH) return i;
  return load_queue_path(pc.queue, i);
}
vec3 path_throughput(uint path) {
  if (PRIMARY_DEPTH) return vec3(1.0f);
  return imageLoad(throughputBuffer, int(path)).xyz;
}
void add_path_radiance(uint path, vec3 radiance) {
  vec4 sum = vec4(0.0f);
  if (!PRIMARY_DEPTH) sum = imageLoad(radianceBuffer, int(path));
  imageStore(radianceBuffer, int(path), sum + vec4(radiance, 0.0f));
}
// A hit as the four words the hit buffer and the caches hold (t bits, triId, u bits, v bits), and back.
uvec4 hit_bits(HtHit h) { return uvec4(floatBitsToUint(h.t), h.triId, floatBitsToUint(h.u), floatBitsToUint(h.v)); }
HtHit hit_of_bits(uvec4 h) { return HtHit(uintBitsToFloat(h.x), h.y, uintBitsToFloat(h.z), uintBitsToFloat(h.w)); }
HtHit load_hit(uint i) { return hit_of_bits(imageLoad(hitBuffer, int(i))); }
void store_hit(uint i, HtHit h) { imageStore(hitBuffer, int(i), hit_bits(h)); }
HtRay load_shadow_ray(uint slot) {
  vec4 a = imageLoad(shadowRayBuffer, int(2u * slot));
  vec4 b = imageLoad(shadowRayBuffer, int(2u * slot + 1u));
  return HtRay(a.xyz, a.w, b.xyz, b.w);
}
void store_shadow_ray(uint slot, HtRay r) {
  imageStore(shadowRayBuffer, int(2u * slot), vec4(r.origin, r.tmin));
  imageStore(shadowRayBuffer, int(2u * slot + 1u), vec4(r.dir, r.tmax));
}

vec3 scene_vertex(uint i) { return texelFetch(vertexTexels, int(i)).xyz; }
// Position and convex part tag (.w, gpu/convex_parts.h) of vertex i.
vec4 scene_vertex_tagged(uint i) { return texelFetch(vertexTexels, int(i)); }
vec3 scene_normal(uint i) { return texelFetch(normalTexels, int(i)).xyz; }
vec2 scene_texcoord(uint i) { return texelFetch(texcoordTexels, int(i)).xy; }
uvec4 scene_triangle(uint i) { return texelFetch(triangleTexels, int(i)); }
GpuMaterial scene_material(uint i) {
  int k = int(3u * i);
  return GpuMaterial(texelFetch(materialTexels, k), texelFetch(materialTexels, k + 1), texelFetch(materialTexels, k + 2));
}
GpuLight scene_light(uint i) {
  int k = int(4u * i);
  return GpuLight(texelFetch(lightTexels, k), texelFetch(lightTexels, k + 1), texelFetch(lightTexels, k + 2),
                  texelFetch(lightTexels, k + 3));
}
GpuTexture scene_texture(uint i) { return GpuTexture(texelFetch(textureTexels, int(i))); }
vec4 scene_texel(uint i) { return texelFetch(texelTexels, int(i)); }

// ht_hash / ht_uint_to_unit (shared with the C++ tests that regenerate sample positions).
#include "camera_models/footprint_sampling.h"
