// scene_edits.h - changes to a loaded Scene without reloading it (holotraced UpdateScene): a node moved to a new
// world matrix, a light's position, direction, colour or intensity. Each edit checks its input first and leaves the
// scene untouched when it throws.
#pragma once
#include <optional>
#include <string_view>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace ht {

// Moves node `name` so that its geometry is transformed by `world` instead of its current matrix:
// p' = W_new W_old^-1 p for positions, n' = normalize(M^-T n) for normals with M = W_new W_old^-1 (normals are
// covectors; pbrt-v4 "Applying Transformations: Normals"), and a change of handedness (det M < 0) swaps two
// corners of each triangle so that front faces stay counter-clockwise (glTF 2.0, Meshes). Throws SceneError for
// an unknown name, a non-finite matrix or one whose upper 3x3 is singular.
void setNodeWorldMatrix(Scene& scene, std::string_view name, const glm::dmat4& world);

struct LightEdit {
  std::optional<glm::dvec3> position, direction, color;  // direction: normalized here; color: linear RGB >= 0
  std::optional<double> intensity;                       // >= 0 (candela or lux, as in glTF)
};
// Throws SceneError for an index out of range, non-finite values, a zero direction or negative colour/intensity.
void editLight(Scene& scene, std::size_t index, const LightEdit& edit);

// The world bounds of the vertices of scene.nodes[index] as they are now (empty for a node without vertices): a
// moved node's bounds before and after setNodeWorldMatrix are what gpu::Renderer::replaceSceneAfterMove takes.
Bounds3 nodeWorldBounds(const Scene& scene, std::size_t index);

// A ball holding every vertex of scene.nodes[index] as it is now: xyz its centre (the bounds' centre), w its radius,
// grown by 1e-6 of the node's extent and of the centre's magnitude over the rounding of its computation (w < 0: the
// node has no vertices). A moved node's balls before and after (gpu::MovedBounds) let the marking pass of a partial
// re-render pass over segments that cross the corners of the moved bounds (docs/REUSE.md §4).
glm::vec4 nodeWorldBall(const Scene& scene, std::size_t index);
// No ball (radius < 0): what nodeWorldBall gives for a node without vertices, and gpu::MovedBounds's default.
inline const glm::vec4 kNoBall(0.0f, 0.0f, 0.0f, -1.0f);

// Index of node `name` in scene.nodes, or nullopt.
std::optional<std::size_t> findNode(const Scene& scene, std::string_view name);

}  // namespace ht
