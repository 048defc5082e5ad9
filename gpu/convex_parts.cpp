// convex_parts.cpp - see convex_parts.h.
#include "gpu/convex_parts.h"

#include "scene/convex_sides.h"

namespace ht::gpu {

static_assert(gpu_shared::HT_CONVEX_FRONT == kConvexFront && gpu_shared::HT_CONVEX_BACK == kConvexBack);

float convexVertexTag(const SceneNode& node, std::size_t instance) {
  if (node.convexSides == 0 || instance + 1 >= gpu_shared::HT_MAX_CONVEX_PARTS) return 0.0f;
  return static_cast<float>(((instance + 1) << gpu_shared::HT_CONVEX_SIDE_BITS) | node.convexSides);
}

std::vector<std::uint32_t> convexPartOfTriangles(const Scene& scene) {
  std::vector<std::uint32_t> parts(scene.triangles.size(), 0u);
  const std::vector<SceneInstance> instances = scene.instances();
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const SceneInstance& inst = instances[i];
    if (inst.node < 0 || convexVertexTag(scene.nodes[static_cast<std::size_t>(inst.node)], i) == 0.0f) continue;
    for (std::uint32_t t = inst.firstTriangle; t < inst.firstTriangle + inst.triangleCount; ++t)
      parts[t] = static_cast<std::uint32_t>(i + 1);
  }
  return parts;
}

void tagConvexParts(bvh::GpuBvh& bvh, const Scene& scene) { bvh::tagTriangleParts(bvh, convexPartOfTriangles(scene)); }

}  // namespace ht::gpu
