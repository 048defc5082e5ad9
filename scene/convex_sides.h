// convex_sides.h - which sides of a node's surface a ray can leave without meeting the node again.
//
// A node whose every vertex lies on or behind the plane of each of its triangles (behind: against the normal its
// winding gives, cross(p1 - p0, p2 - p0)) is convex with the front sides outside: a ray that leaves one of its
// triangles on the front side moves away from that plane, and every point of the node lies behind it, so the ray
// cannot meet the node again. Shadow rays from such a surface skip the node in the traversal (the walk of its
// bottom level on a two-level BVH, its triangles on a flattened one; docs/BVH.md §9.6): the same occlusion with
// fewer steps, and no self-shadowing "acne" from rounding. The back sides likewise, with every vertex on or in front.
#pragma once
#include <cstdint>

#include "scene/scene.h"

namespace ht {

inline constexpr std::uint8_t kConvexFront = 1;  // a ray leaving a triangle on its winding normal's side
inline constexpr std::uint8_t kConvexBack = 2;   // ... on the other side
// Triangle x vertex plane tests one node may take (a 5,120-triangle icosphere takes 13 M, about 10 ms); a larger
// node is reported as not convex rather than delaying the load.
inline constexpr std::uint64_t kMaxConvexPlaneTests = std::uint64_t{1} << 26;
// Plane tests markConvexNodes may take for one scene (about 0.15 s on one core here): a scene of many distinct large
// convex meshes leaves the rest unmarked rather than delaying its load.
inline constexpr std::uint64_t kMaxConvexPlaneTestsPerScene = std::uint64_t{1} << 27;
// How far (relative to the node's bounding-box diagonal) a vertex may lie beyond a plane and still count as on it:
// float rounding of coplanar vertices (a box's face is two triangles), far below any visible feature.
inline constexpr double kConvexPlaneTolerance = 1e-6;

// The sides (kConvexFront | kConvexBack bits) of `node`'s triangles that lie outside the node; 0 when neither does
// (not convex), when a triangle indexes a vertex outside the node's own range, or when the node has more than
// kMaxConvexPlaneTests plane tests. A flat node (every vertex in one plane) has both sides outside.
// `planeTests` (optional): adds the plane tests taken (a node that is not convex usually stops after a few planes).
std::uint8_t convexSides(const Scene& scene, const SceneNode& node, std::uint64_t* planeTests = nullptr);

// Sets SceneNode::convexSides of every node (the glTF loader calls it; setNodeWorldMatrix keeps it true: an affine
// map keeps a convex node convex, and a mirroring one is given the opposite winding), within
// kMaxConvexPlaneTestsPerScene. Returns how many nodes it left unmarked for lack of that budget.
std::size_t markConvexNodes(Scene& scene);

}  // namespace ht
