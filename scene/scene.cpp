// scene.cpp - Scene queries: bounds and the feature flags renderers use to pick code paths.
#include "scene/scene.h"

#include <algorithm>
#include <cmath>

namespace ht {
namespace {

bool isFinite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

}  // namespace

// Bounds of the finite vertices that triangles reference (NaN/Inf vertices are dropped by the BVH too).
Bounds3 Scene::bounds() const {
  Bounds3 b;
  for (const glm::uvec3& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = t[k];
      if (v < positions.size() && isFinite(positions[v])) b.extend(positions[v]);
    }
  return b;
}

// Node ranges in triangle order, with the gaps between them (and before/after them) as node-less instances.
std::vector<SceneInstance> Scene::instances() const {
  std::vector<SceneInstance> ranges;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    if (nodes[n].triangleCount == 0) continue;
    ranges.push_back({nodes[n].firstTriangle, nodes[n].triangleCount, nodes[n].mesh, static_cast<std::int32_t>(n)});
  }
  std::sort(ranges.begin(), ranges.end(),
            [](const SceneInstance& a, const SceneInstance& b) { return a.firstTriangle < b.firstTriangle; });
  std::vector<SceneInstance> out;
  std::uint32_t next = 0;
  auto addGap = [&](std::uint32_t end) {
    if (end > next) out.push_back({next, end - next, -1, -1});
  };
  for (const SceneInstance& r : ranges) {
    addGap(r.firstTriangle);
    out.push_back(r);
    next = std::max(next, r.firstTriangle + r.triangleCount);
  }
  addGap(static_cast<std::uint32_t>(triangles.size()));
  return out;
}

// Features of the materials that triangles actually use (a glTF file may define unused materials), plus
// whether any light exists.
SceneFeatures Scene::features() const {
  std::vector<bool> used(materials.size(), false);
  for (std::uint32_t m : triangleMaterial)
    if (m < used.size()) used[m] = true;

  SceneFeatures f;
  f.lights = !lights.empty();
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (!used[i]) continue;
    const Material& m = materials[i];
    f.mirrors |= m.kind() == MaterialKind::Mirror;
    f.glass |= m.kind() == MaterialKind::Glass;
    f.textures |= m.baseColorTexture >= 0 && static_cast<std::size_t>(m.baseColorTexture) < textures.size();
    f.emissive |= m.emissive.x > 0.0f || m.emissive.y > 0.0f || m.emissive.z > 0.0f;
  }
  return f;
}

}  // namespace ht
