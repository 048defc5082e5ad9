// convex_parts.cpp - see convex_parts.h.
#include "gpu/convex_parts.h"

#include <algorithm>

#include "scene/convex_sides.h"

namespace ht::gpu {

static_assert(gpu_shared::HT_CONVEX_FRONT == kConvexFront && gpu_shared::HT_CONVEX_BACK == kConvexBack);

float convexVertexTag(const SceneNode& node, std::size_t instance) {
  if (node.convexSides == 0 || instance + 1 >= gpu_shared::HT_MAX_CONVEX_PARTS) return 0.0f;
  return static_cast<float>(((instance + 1) << gpu_shared::HT_CONVEX_SIDE_BITS) | node.convexSides);
}

namespace {

// Calls visit(instance index, its node, its tag) for every instance of `scene` on a convex part.
template <class Visit>
void forEachConvexPart(const Scene& scene, Visit visit) {
  const std::vector<SceneInstance> instances = scene.instances();
  for (std::size_t i = 0; i < instances.size(); ++i) {
    if (instances[i].node < 0) continue;
    const SceneNode& node = scene.nodes[static_cast<std::size_t>(instances[i].node)];
    const float tag = convexVertexTag(node, i);
    if (tag != 0.0f) visit(i, instances[i], node, tag);
  }
}

}  // namespace

std::vector<std::uint32_t> convexPartOfTriangles(const Scene& scene) {
  std::vector<std::uint32_t> parts(scene.triangles.size(), 0u);
  forEachConvexPart(scene, [&](std::size_t i, const SceneInstance& inst, const SceneNode&, float) {
    std::fill_n(parts.begin() + inst.firstTriangle, inst.triangleCount, static_cast<std::uint32_t>(i + 1));
  });
  return parts;
}

std::vector<float> convexVertexTags(const Scene& scene) {
  std::vector<float> tags(scene.positions.size(), 0.0f);
  forEachConvexPart(scene, [&](std::size_t, const SceneInstance&, const SceneNode& node, float tag) {
    if (std::uint64_t{node.firstVertex} + node.vertexCount <= tags.size())  // (a marked node owns its range)
      std::fill_n(tags.begin() + node.firstVertex, node.vertexCount, tag);
  });
  return tags;
}

void tagConvexParts(bvh::GpuBvh& bvh, const Scene& scene) { bvh::tagTriangleParts(bvh, convexPartOfTriangles(scene)); }

}  // namespace ht::gpu
