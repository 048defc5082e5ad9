// convex_parts.h - the convex parts of a scene on the GPU (docs/BVH.md §9.6), one source for shade.comp and the host.
//
// Part p (p >= 1) is instance p - 1 of Scene::instances() when its node is convex (SceneNode::convexSides,
// scene/convex_sides.h): on a two-level BVH that instance's bottom level (its index + 1 is the part), on a flattened
// one the triangles whose slots carry p (bvh/gpu_node.h, vertex 1's .w). Each vertex of the part carries
// (p << 2) | sides in its .w (the vertex buffer, GpuScene), so shade learns from the hit triangle's first vertex,
// which it loads anyway, which part a shadow ray or a bounce leaves and whether it leaves on the outside.
#ifndef HT_CONVEX_PARTS_H
#define HT_CONVEX_PARTS_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

HT_CONST uint HT_CONVEX_FRONT = 1u;  // = ht::kConvexFront: rays leaving the winding normal's side are outside
HT_CONST uint HT_CONVEX_BACK = 2u;   // = ht::kConvexBack
HT_CONST uint HT_CONVEX_SIDE_BITS = 2u;
// Parts below this keep their vertex tag exact as a float (2^24 / 4).
HT_CONST uint HT_MAX_CONVEX_PARTS = 1u << 22;

// The part a ray leaving a surface point of a triangle whose first vertex has tag `vertexTag` leaves on the outside
// (`front`: the point is on the winding normal's side; the ray leaves on that side), 0 when none.
HT_INLINE uint ht_convex_part_left(float vertexTag, bool front) {
  uint tag = uint(vertexTag);
  uint side = front ? HT_CONVEX_FRONT : HT_CONVEX_BACK;
  return (tag & side) != 0u ? tag >> HT_CONVEX_SIDE_BITS : 0u;
}

HT_SHARED_END

#ifndef HT_GLSL
#include <vector>

#include "bvh/gpu_layout.h"
#include "scene/scene.h"

namespace ht::gpu {

// The vertex tag of node `node` as instance `instance` of Scene::instances() (0: not convex, or too many parts).
float convexVertexTag(const SceneNode& node, std::size_t instance);
// The part of every triangle of `scene` (0: none), in triangle order.
std::vector<std::uint32_t> convexPartOfTriangles(const Scene& scene);
// The tag of every vertex of `scene` (0: on no convex part), in vertex order.
std::vector<float> convexVertexTags(const Scene& scene);
// Tags the slots of a flattened BVH of `scene` with their triangles' parts (bvh/gpu_node.h).
void tagConvexParts(bvh::GpuBvh& bvh, const Scene& scene);

}  // namespace ht::gpu
#endif
#endif
