// bvh_access.glsl - how the trace kernels read the BVH (defines the accessors bvh/bvh_traversal.h uses).
//
// TEXEL_FETCH = true (default): nodes and triangles are read through uniform texel buffers. Mesa 22.3's
// lavapipe turns every 32-bit component of a storage-buffer or buffer-device-address load into a loop over the
// 8 SIMD lanes (gallivm lp_bld_nir_soa.c emit_load_global / emit_load_mem), while a texel fetch loads all lanes
// at once; GPUs read texel buffers through the texture cache (as the Aila-Laine kernels did). Integer fields
// (child links, triangle-id bits, which as floats are denormals) come through UINT views of the same memory,
// so no float path can flush them.
// TEXEL_FETCH = false: buffer device addresses, for BVHs larger than maxTexelBufferElements.
layout(constant_id = HT_SPEC_TEXEL_FETCH) const bool TEXEL_FETCH = true;
// TWO_LEVEL = true: the BVH bindings hold the bottom levels of a two-level BVH (bvh/two_level_bvh.h), whose top level
// and instance table are read through texel fetches always (a few nodes per instance).
layout(constant_id = HT_SPEC_TWO_LEVEL) const bool TWO_LEVEL = false;

layout(set = 0, binding = HT_BINDING_BVH_NODES) uniform samplerBuffer bvhNodeTexels;      // 4 texels per node
layout(set = 0, binding = HT_BINDING_BVH_NODE_UINTS) uniform usamplerBuffer bvhNodeUintTexels; // same memory, integer view
layout(set = 0, binding = HT_BINDING_BVH_TRIS) uniform samplerBuffer bvhTriTexels;       // 3 texels per triangle slot
layout(set = 0, binding = HT_BINDING_BVH_TRI_UINTS) uniform usamplerBuffer bvhTriUintTexels;  // same memory, integer view

GpuBvhNode ht_fetch_node(uint i) {
  if (TEXEL_FETCH) {
    GpuBvhNode n;
    int base = int(4u * i);
    n.c0xy = texelFetch(bvhNodeTexels, base);
    n.c1xy = texelFetch(bvhNodeTexels, base + 1);
    n.c01z = texelFetch(bvhNodeTexels, base + 2);
    n.link = texelFetch(bvhNodeUintTexels, base + 3);
    return n;
  }
  return NodeRef(pc.nodes).n[i];
}

uvec4 ht_fetch_node_link(uint i) {
  if (TEXEL_FETCH) return texelFetch(bvhNodeUintTexels, int(4u * i + 3u));
  return NodeRef(pc.nodes).n[i].link;
}

vec4 ht_fetch_tri(uint i) {
  if (TEXEL_FETCH) return texelFetch(bvhTriTexels, int(i));
  return Vec4Ref(pc.bvhTriangles).v[i];
}

uint ht_fetch_tri_id(uint slot) {
  if (TEXEL_FETCH) return texelFetch(bvhTriUintTexels, int(slot)).w;
  return floatBitsToUint(Vec4Ref(pc.bvhTriangles).v[slot].w);
}

layout(set = 0, binding = HT_BINDING_TOP_NODES) uniform samplerBuffer topNodeTexels;         // 4 texels per node
layout(set = 0, binding = HT_BINDING_TOP_NODE_UINTS) uniform usamplerBuffer topNodeUintTexels; // same memory, integer view
layout(set = 0, binding = HT_BINDING_INSTANCES) uniform usamplerBuffer instanceTexels;        // 1 texel per entry

GpuBvhNode ht_fetch_top_node(uint i) {
  GpuBvhNode n;
  int base = int(4u * i);
  n.c0xy = texelFetch(topNodeTexels, base);
  n.c1xy = texelFetch(topNodeTexels, base + 1);
  n.c01z = texelFetch(topNodeTexels, base + 2);
  n.link = texelFetch(topNodeUintTexels, base + 3);
  return n;
}

#define HT_LOAD_TOP_NODE(i) ht_fetch_top_node(i)
#define HT_LOAD_INSTANCE(i) texelFetch(instanceTexels, int(i))
#define HT_LOAD_NODE(i) ht_fetch_node(i)
#define HT_LOAD_NODE_LINK(i) ht_fetch_node_link(i)
#define HT_LOAD_TRI(i) ht_fetch_tri(i)
#define HT_LOAD_TRI_ID(slot) ht_fetch_tri_id(slot)
