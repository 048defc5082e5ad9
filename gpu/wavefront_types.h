// wavefront_types.h - data shared by the host (C++) and every wavefront pass (GLSL): the per-frame block of
// buffer device addresses and parameters, scene records (materials, lights, texture directory) and the
// layout of the queues. All buffers are reached through VK_KHR_buffer_device_address, so no buffer is bound
// through a descriptor and lavapipe's 128 MiB maxStorageBufferRange (docs/TOOLCHAIN.md §4, P10) does not apply.
//
// Pass order per batch of paths (docs/BVH.md §7, "proposed holotrace passes"):
//   raygen -> [trace_closest -> shade -> (prepare -> trace_any -> gather_direct)? -> prepare]* -> resolve
// and once per frame: interleave. Queues are compacted with atomic counters; a `prepare` invocation turns a
// counter into vkCmdDispatchIndirect arguments, so an empty queue dispatches zero workgroups.
#ifndef HT_WAVEFRONT_TYPES_H
#define HT_WAVEFRONT_TYPES_H
#include "common/glsl_cpp.h"
#include "camera_models/model_list.h"
#include "gpu/segment_cells.h"
#include "gpu/shader_interface.h"

HT_SHARED_BEGIN

#ifndef HT_GLSL
using uint64_t = std::uint64_t;
#endif

HT_CONST uint HT_WORKGROUP_SIZE = 64u;
HT_CONST uint HT_MAX_LIGHTS = 16u;
// Moved instances a partial re-render's primary rays may walk alone (FrameBlock::movedInstanceIds, one uvec4); more
// moved instances since the last frame: those rays are traced whole.
HT_CONST uint HT_MAX_WALKED_INSTANCES = 4u;
// A bounce link that names no entry of the bounce cache (FrameBlock::bounceFirst).
HT_CONST uint HT_NO_BOUNCE = 0xFFFFFFFFu;
// Frame reuse's shadow-occlusion cache (gpu/frame_reuse.h ReusePlan::occlusionDepths, docs/REUSE.md §3): a word per
// depth and frame path, bit l = the path's shadow ray to light l was occluded, bit HT_OCCLUSION_TRACED_SHIFT + l =
// that ray was traced since the path's hit at that depth was found (16 lights at most, so both fit).
HT_CONST uint HT_OCCLUSION_TRACED_SHIFT = 16u;
// shade.comp OCCLUSION: what shade takes from the cache (nothing, the lights a light edit kept, the segments a move
// kept at depth 0 of a partial re-render); every mode but OFF rewrites the words of the paths it shades.
HT_CONST uint HT_OCCLUSION_OFF = 0u;
HT_CONST uint HT_OCCLUSION_RECORD = 1u;
HT_CONST uint HT_OCCLUSION_KEPT_LIGHTS = 2u;
HT_CONST uint HT_OCCLUSION_KEPT_SEGMENTS = 3u;
// trace_any.comp SHADOW_CACHE: where the traced rays' occlusion goes (the batch's own paths, or listed targets').
HT_CONST uint HT_SHADOW_CACHE_OFF = 0u;
HT_CONST uint HT_SHADOW_CACHE_RECORD = 1u;
HT_CONST uint HT_SHADOW_CACHE_RECORD_LISTED = 2u;
// A shadow-queue entry with this bit (over its slot) was unoccluded when recorded and its path kept its hit: only the
// moved instances can occlude it now, so trace_any walks their bottom levels alone (shade.comp KEPT_SEGMENTS). Slots
// (path x lights + light) stay far below 2^31: a batch's shadow rays fit one storage buffer (32 B each).
HT_CONST uint HT_SHADOW_MOVED_ONLY = 0x80000000u;

// Material kinds (scene.h MaterialKind) and light types (scene.h Light::Type).
HT_CONST uint HT_MATERIAL_DIFFUSE = 0u;
HT_CONST uint HT_MATERIAL_MIRROR = 1u;
HT_CONST uint HT_MATERIAL_GLASS = 2u;
HT_CONST uint HT_LIGHT_POINT = 0u;
HT_CONST uint HT_LIGHT_SPOT = 1u;
HT_CONST uint HT_LIGHT_DIRECTIONAL = 2u;

struct GpuMaterial {
  vec4 baseColor;  // rgb linear; w = texture index (as float, -1 = none)
  vec4 emissive;   // rgb radiance; w = kind (HT_MATERIAL_*) as float
  vec4 params;     // metallic, roughness, transmission, ior
};

struct GpuLight {
  vec4 position;   // xyz world position; w = type (HT_LIGHT_*) as float
  vec4 direction;  // xyz unit direction the light travels; w = range (0 = infinite)
  vec4 radiance;   // rgb = color * intensity (cd or lux); w unused
  vec4 cone;       // x = cos(outer), y = cos(inner) (spot); zw unused
};

struct GpuTexture {
  uvec4 info;  // x = first texel index, y = width, z = height, w unused
};

// Counters written by the passes; the host reads the whole block back after a frame.
struct GpuCounters {
  uint queueCount[2];  // entries in ray queue 0 / 1 (ping-pong)
  uint shadowCount;    // entries in the shadow queue
  uint overflowCount;  // rays that hit the traversal step limit (must stay 0)
  uint maxSteps;       // largest traversal step count seen
  uint raysTraced;     // closest + any rays traced in this frame
  uint nanCount;       // non-finite radiance values clamped to 0 (must stay 0)
  uint subgroupSize;   // written by refine_select: the subgroup size its dispatch ran with
  uvec4 dispatch[3];   // indirect dispatch args: [0] queue 0, [1] queue 1, [2] shadow queue (xyz, w unused)
};

// One block per frame, in a uniform buffer (binding HT_BINDING_FRAME). Every member is 16-byte aligned, so the
// std140 layout GLSL uses equals the C++ layout. Per-path state and scene records are texel buffers (see
// gpu/shaders/common.glsl for why). The atomic counters, the BVH fallback and the writers of the frame-reuse state
// reach their buffers by address.
struct FrameBlock {
  uint64_t counters;   // GpuCounters (device address)
  uint64_t refine;     // adaptive refinement: slot counts, staging, the refined targets (device address)
  uvec4 dims;          // x = image width, y = image height (one view), z = spp, w = number of targets
  uvec4 views;         // x = views in this frame, y = index of its first view, z = filter (HT_FILTER_*),
                       // w = first row of the band (from the bottom) this chunk renders of each view
  uvec4 scene;         // x = light count, y = texture count, z = step limit, w = max depth
  uvec4 frame;         // x = seed, y = rows of a whole view (dims.y: of the band), z = targets per pixel;
                       // w = the lights whose recorded shadow occlusion a frame re-shaded from cached hits keeps
                       // (ReusePlan::keptLightRays; set after the frame's reuse key is taken, 0 otherwise)
  uvec4 refineInfo;    // adaptive refinement (refine_select.comp): x = contrast threshold (float bits), y = first
                       // entry of the target list in `refine` (!= 0 while listed targets are traced: refinement
                       // or a partial re-render, gpu/frame_reuse.h), z = subgroup size the slots assume,
                       // w = the base pass's spp while refined targets are traced (resolve.comp averages
                       // its samples with theirs), 0 otherwise
  uvec4 flags;         // x = scene has vertex normals, y = scene has texcoords
  vec4 background;     // rgb radiance of escaped rays
  vec4 ambient;        // rgb ambient irradiance on diffuse surfaces
  CameraBlock camera;  // the frame's camera model's parameters (camera_models/model_list.h)
  // Progressive accumulation (gpu/accumulator.h, docs/REUSE.md §1): accum.x = 1 while a frame adds samples to the
  // accumulation's sums (AccumTarget per target of the whole frame, by frame_global_target, in the storage texel
  // buffers HT_BINDING_ACCUM_SUMS and _HALVES), 0 for single frames; y = the target error (float bits), z = min spp,
  // w = max spp of the stop rule (gpu/accumulation_error.h).
  uint64_t accumReserved;  // 0 (keeps the members below on 16-byte boundaries)
  uint64_t accumStats;     // AccumStats of the frame (device address)
  uvec4 accum;
  // ... the accumulation's target list (device address, a uint per entry): the targets its last frame sampled, which
  // the next frame's selection re-judges (a target left out stays converged: its sums no longer change), and which
  // its show pass shows (accum_show.comp LISTED); and the stop-rule statistics of the targets left out of that list
  // (AccumStats; gathered by refine_select.comp BY_ERROR as it leaves them out, docs/REUSE.md §2).
  uint64_t accumList;
  uint64_t accumSettledStats;
  // Frame reuse (gpu/frame_reuse.h): per-target segment cells, 4 words per target (device address; 0 = the frame
  // records none), the cached primary rays and hits of every path (HtRay / HtHit per path in path order; 0 = none:
  // then the masks hold the primary segments too) and the world grid the cells are counted on (segment_cells.h).
  // Their readers use the texel views HT_BINDING_REUSE_* of the same buffers.
  uint64_t segmentMasks;
  uint64_t primaryRays;
  uint64_t primaryHits;
  // ... and the occlusion of every path's shadow rays, a word per depth and path (device address; 0 = none;
  // gpu/frame_reuse.h ReusePlan::occlusionDepths, shade.comp OCCLUSION, trace_any.comp SHADOW_CACHE).
  uint64_t shadowOcclusion;
  SegmentGrid grid;
  // The inputs of a marking pass and a partial re-render (FrameReuseState::writeMarkingInputs; 0 otherwise), here
  // rather than in the dirty list's header because uniform loads are scalar on lavapipe, where a load by device
  // address is a loop over the 8 lanes: the padded moved bounds (xyz; lo > hi: none), and moved = (the moved bounds'
  // grid cells, words 0-1; the first list entry of the candidates of the exact tests, 0: none; the bounce cache's
  // entries, with ReusePlan::secondaryExact).
  vec4 movedLo;
  vec4 movedHi;
  uvec4 moved;
  // ... and balls around the moved geometry before and after its move (xyz centre, w radius; w < 0: none), which a
  // segment that meets the padded moved bounds must also come near to count (gpu/segment_cells.h
  // ht_segment_meets_balls; ReusePlan::movedBalls).
  vec4 movedBalls[2];
  // ... and, on a two-level BVH whose moves since the last frame name their instances (Renderer::moveNodes), those
  // instances: their instance indices in movedInstanceIds, 0xFFFFFFFF past the last (all: none, or not known), and
  // the scene triangles of each in movedTriangles (first, count). A traced ray of a partial re-render walks from its
  // cached hit: only their bottom levels when that hit is on none of them, the others' only beyond it when it is on
  // one (trace_closest.comp REUSE_PRIMARY and REUSE_BOUNCES, bvh/ordered_traversal.h ht_trace_two_level_after_moves).
  uvec4 movedInstanceIds;
  uvec4 movedTriangles[HT_MAX_WALKED_INSTANCES];
  // The links of the bounce cache (gpu/frame_reuse.h FrameReuseState::bounceFirst, docs/REUSE.md §4 "Bounce rays
  // that take their cached hits"): bounceFirst, the entry of each frame path's depth-1 ray (device address, a uint per
  // path; 0 = none); bounceNext, the entry of the next depth's ray of the same path, per entry (the cache's `nexts`,
  // device address; 0 = none). HT_NO_BOUNCE: the path does not go on. A frame that fills the cache writes them
  // (shade.comp LINK_BOUNCES) with bounceLinks.x = the first entry of the shaded queue (depths >= 1), .y = the first
  // entry the next depth's queue will take; a partial re-render reads them (trace_closest.comp REUSE_BOUNCES).
  uint64_t bounceFirst;
  uint64_t bounceNext;
  uvec4 bounceLinks;
};

// The accumulated samples of one target (docs/REUSE.md §1-§2): the sum of its n samples in sample order, and the
// sum of its half-estimate samples (gpu/accumulation_error.h). 32 B; vec3 + uint packs to 16 B in std430 and C++.
struct AccumTarget {
  vec3 sum;
  uint n;
  vec3 halfSum;
  uint halfN;
};

// Written by accum_show.comp over the targets a progressive frame shows (atomics; reset by the host per frame), and
// by refine_select.comp over the targets its selection leaves out for good ("settled": reset when it judges all).
struct AccumStats {
  uint unconverged;   // targets the stop rule says need more samples
  uint maxErrorBits;  // largest error estimate (float bits; non-negative floats order as their bits)
  uint minSamples;    // fewest samples of a target
  uint maxSamples;    // most samples of a target
};

// Push constants of every pass (40 B of the 128 B guaranteed). The BVH addresses sit here, not in the
// FrameBlock, so the traversal loop reads them without an extra dependent load per node fetch.
struct PassConstants {
  uint64_t frame;         // address of the FrameBlock
  uint64_t nodes;         // == FrameBlock.nodes
  uint64_t bvhTriangles;  // == FrameBlock.bvhTriangles
  uint batchFirst;        // first path index of this batch (a multiple of spp)
  uint batchCount;        // paths in this batch
  uint depth;             // bounce number of the current queue (0 = primary rays)
  uint queue;             // input ray queue (0/1); output queue = 1 - queue
};

HT_SHARED_END
#endif
