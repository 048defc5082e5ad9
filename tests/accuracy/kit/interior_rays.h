// interior_rays.h - rays that start strictly inside a closed TestMesh (every one must hit it).
//
// Kinds, after Embree verify's watertight test (random origins and directions inside a sphere) and tinybvh's
// axis_ray_test (axis-aligned rays through shared edges and vertices), docs/BVH.md §6:
//   Random      uniform direction
//   Vertex      aimed exactly at a mesh vertex (direction = vertex - origin, in float)
//   Edge        aimed at the midpoint of a mesh edge
//   Axis        +-x, +-y or +-z (two zero direction components)
//   ZeroComp    uniform direction in a coordinate plane (one zero component)
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bvh/ray_types.h"
#include "test_meshes.h"

namespace ht::accuracy {

enum class RayKind : uint32_t { Random = 0, Vertex, Edge, Axis, ZeroComp, Count };
std::string rayKindName(RayKind kind);

// `count` rays of one kind, reproducible from `seed`. tmin = 0, tmax = 3e38.
std::vector<gpu_shared::HtRay> interiorRays(const TestMesh& mesh, RayKind kind, uint32_t count, uint32_t seed);

// `count` rays with the kinds mixed in equal parts, ZeroComp first and Random last (with the remainder).
std::vector<gpu_shared::HtRay> mixedInteriorRays(const TestMesh& mesh, uint32_t count, uint32_t seed);

}  // namespace ht::accuracy
