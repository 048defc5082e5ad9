// shader_interface.h - the one source of the numbers the host and the GLSL passes must agree on: the bindings of
// descriptor set 0 and the specialisation-constant ids shared by several kernels. The C++ side (frame_descriptors,
// renderer) and the shaders (gpu/shaders/common.glsl, bvh_access.glsl) both name these constants; no binding or
// shared constant id is written as a literal anywhere else. Shared-header rules: common/glsl_cpp.h.
#ifndef HT_SHADER_INTERFACE_H
#define HT_SHADER_INTERFACE_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

// Descriptor set 0. Why texel buffers: gpu/shaders/common.glsl.
// BVH views (bvh_access.glsl), uniform texel buffers; the UINT views alias the same memory.
HT_CONST uint HT_BINDING_BVH_NODES = 0u;       // RGBA32F, 4 texels per node
HT_CONST uint HT_BINDING_BVH_NODE_UINTS = 1u;  // RGBA32UI view of the nodes
HT_CONST uint HT_BINDING_BVH_TRIS = 2u;        // RGBA32F, 3 texels per triangle slot
HT_CONST uint HT_BINDING_BVH_TRI_UINTS = 3u;   // RGBA32UI view of the triangle slots
HT_CONST uint HT_BINDING_FRAME = 4u;           // uniform buffer: FrameBlock (gpu/wavefront_types.h)
// Per-path state and the frame's outputs, storage texel buffers.
HT_CONST uint HT_BINDING_RAY_QUEUE_0 = 5u;  // RGBA32F, 2 texels per ray
HT_CONST uint HT_BINDING_RAY_QUEUE_1 = 6u;
HT_CONST uint HT_BINDING_QUEUE_PATH_0 = 7u;  // R32UI
HT_CONST uint HT_BINDING_QUEUE_PATH_1 = 8u;
HT_CONST uint HT_BINDING_HITS = 9u;             // RGBA32UI: t bits, triId, u bits, v bits
HT_CONST uint HT_BINDING_RADIANCE = 10u;        // RGBA32F
HT_CONST uint HT_BINDING_THROUGHPUT = 11u;      // RGBA32F
HT_CONST uint HT_BINDING_SHADOW_RAYS = 12u;     // RGBA32F, 2 texels per slot
HT_CONST uint HT_BINDING_SHADOW_CONTRIB = 13u;  // RGBA32F
HT_CONST uint HT_BINDING_SHADOW_QUEUE = 14u;    // RG32UI: slot (| HT_SHADOW_MOVED_ONLY), convex part it leaves
HT_CONST uint HT_BINDING_SUBPIXELS = 15u;       // R32F: one value per target
HT_CONST uint HT_BINDING_OUTPUT_IMAGE = 16u;    // RGBA32F: the views, read back by the host
// Scene records, uniform texel buffers.
HT_CONST uint HT_BINDING_VERTICES = 17u;
HT_CONST uint HT_BINDING_NORMALS = 18u;
HT_CONST uint HT_BINDING_TEXCOORDS = 19u;  // RG32F
HT_CONST uint HT_BINDING_TRIANGLES = 20u;  // RGBA32UI: i0, i1, i2, material
HT_CONST uint HT_BINDING_MATERIALS = 21u;  // 3 texels per GpuMaterial
HT_CONST uint HT_BINDING_LIGHTS = 22u;     // 4 texels per GpuLight
HT_CONST uint HT_BINDING_TEXTURES = 23u;   // RGBA32UI: GpuTexture.info
HT_CONST uint HT_BINDING_TEXELS = 24u;
HT_CONST uint HT_BINDING_RAY_TABLE = 25u;        // 2 texels per entry: origin, direction
HT_CONST uint HT_BINDING_SUBPIXEL_TEXELS = 26u;  // read-only texel view of HT_BINDING_SUBPIXELS
// Two-level BVH (issue 16, bvh_access.glsl): the top level and the instance table, uniform texel buffers; with the
// flattened BVH they hold a dummy entry. The BVH bindings above then hold the instances' bottom levels.
HT_CONST uint HT_BINDING_TOP_NODES = 27u;       // RGBA32F, 4 texels per node
HT_CONST uint HT_BINDING_TOP_NODE_UINTS = 28u;  // RGBA32UI view of the top nodes
HT_CONST uint HT_BINDING_INSTANCES = 29u;       // RGBA32UI: nodeBase, slotBase, instance, 0
// What the marking pass and a partial re-render read of the frame-reuse state (gpu/frame_reuse.h, reuse_cache.glsl),
// uniform texel views of buffers their writers reach by device address; a 1-texel dummy where none is bound
// (Renderer::Impl::bindReuseTexels).
HT_CONST uint HT_BINDING_REUSE_MASKS = 30u;         // RGBA32UI: a target's 4 mask words per texel
HT_CONST uint HT_BINDING_REUSE_PRIMARY_RAYS = 31u;  // RGBA32F, 2 texels per path
HT_CONST uint HT_BINDING_REUSE_PRIMARY_HITS = 32u;  // RGBA32UI, 1 texel per path
HT_CONST uint HT_BINDING_REUSE_BOUNCES = 33u;       // RGBA32UI view of the bounce cache (FrameReuseState)
// A progressive accumulation's sums (gpu/accumulator.h), storage texel buffers of one texel per target of the whole
// frame; a 1-texel dummy outside accumulations.
HT_CONST uint HT_BINDING_ACCUM_SUMS = 34u;    // RGBA32UI: AccumTarget sum (float bits), n
HT_CONST uint HT_BINDING_ACCUM_HALVES = 35u;  // RGBA32UI: AccumTarget halfSum (float bits), halfN
// The convex part each bounce ray of ray queue q leaves (shade.comp writes it, trace_closest reads it; 0 for none):
// R32UI, entry q * batchCount + slot.
HT_CONST uint HT_BINDING_QUEUE_LEAVES = 36u;
HT_CONST uint HT_BINDING_COUNT = 37u;
// The storage texel buffers are the bindings [FIRST, LAST] and the accumulation's two.
HT_CONST uint HT_BINDING_STORAGE_FIRST = HT_BINDING_RAY_QUEUE_0;
HT_CONST uint HT_BINDING_STORAGE_LAST = HT_BINDING_OUTPUT_IMAGE;

// Specialisation-constant ids. A kernel's own constants take ids from 0 (declared in its .comp file, given by the
// host in that order); the constants of the shared includes sit at fixed higher ids, so they never collide.
HT_CONST uint HT_SPEC_MODEL = 0u;           // raygen, resolve, refine_select: the camera model (HT_MODEL_*)
HT_CONST uint HT_SPEC_TEXEL_FETCH = 10u;    // bvh_access.glsl: read the BVH through texel buffers, else by address
HT_CONST uint HT_SPEC_TWO_LEVEL = 11u;      // bvh_access.glsl: trace the two-level BVH (else the flattened one)
HT_CONST uint HT_SPEC_PRIMARY_DEPTH = 20u;  // common.glsl: the dispatch continues primary paths (depth 0)

HT_SHARED_END
#endif
