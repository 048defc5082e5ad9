// gpu_node.h - the 64-byte two-child BVH node traversed on the GPU and by the CPU reference.
//
// Layout after Aila & Laine 2009 ("Compact2", also tinybvh BVH_GPU; docs/BVH.md §2.4, §3): a node stores the
// boxes of BOTH children, so one 64 B fetch tests two boxes.
//   c0xy = (c0.lo.x, c0.hi.x, c0.lo.y, c0.hi.y)
//   c1xy = (c1.lo.x, c1.hi.x, c1.lo.y, c1.hi.y)
//   c01z = (c0.lo.z, c0.hi.z, c1.lo.z, c1.hi.z)
//   link = (ref0, ref1, count0, count1): count k == 0 -> ref k is an inner node index;
//          count k  > 0 -> child k is a leaf of `count` triangles starting at triangle slot ref k.
// An absent child (only when the whole tree is one leaf) has an empty box (lo = +inf, hi = -inf).
// Triangles are stored in leaf order as 3 x vec4 per slot (HT_TRI_STRIDE); vertex 0's .w holds the
// original triangle id as uint bits (floatBitsToUint / glm::floatBitsToUint); vertex 1's .w the convex part the
// triangle belongs to, as a float value (0 = none; a ray leaving that part skips it, docs/BVH.md §9.6).
#ifndef HT_GPU_NODE_H
#define HT_GPU_NODE_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

struct GpuBvhNode {
  vec4 c0xy;
  vec4 c1xy;
  vec4 c01z;
  uvec4 link;
};

HT_CONST uint HT_TRI_STRIDE = 3u;                // vec4s per triangle slot
HT_CONST uint HT_BVH_MAX_DEPTH = 64u;            // builder guarantee; traversal stack size
HT_CONST uint HT_TRAVERSAL_STEP_LIMIT = 60000u;  // < lavapipe's 65,535 loop budget (docs/TOOLCHAIN.md §0)

HT_SHARED_END
#endif
