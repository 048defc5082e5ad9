// test_meshes.h - closed meshes (icospheres, tori) and their placements for the accuracy suite.
//
// A closed mesh is one whose triangles share every edge with exactly one other triangle, so a ray starting
// strictly inside must hit it: a miss is a leak of the intersection code. Placements follow Embree verify's
// watertight test (tutorials/verify/verify.cpp: sphere of radius 2 centred at (148376, 1234, -223423),
// docs/BVH.md §6) and the scale sweep of docs/BVH.md §6 ("scales from 1e-3 to 1e5", widened here to 1e-4 … 1e4).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace ht::accuracy {

// Where interior ray origins may be drawn: a ball (icosphere) or a tube around a circle in the xz plane
// (torus), in the mesh's own units before placement.
struct Interior {
  enum class Kind { Ball, Tube } kind = Kind::Ball;
  float radius = 0.0f;        // ball radius, or tube radius around the centre circle
  float circleRadius = 0.0f;  // Tube only: radius of the centre circle
};

struct TestMesh {
  std::string name;  // e.g. "icosphere-s4"
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;
  bool closed = true;
  Interior interior;       // valid when closed
  glm::vec3 offset{0.0f};  // placement: world = local * scale + offset
  float scale = 1.0f;
};

// Unit icosphere at the origin, `subdivisions` in [0, 7] (scene/mesh_generators.h). Interior: ball of
// radius 0.5 (the icosahedron's inradius is 0.795, and subdivision only moves the surface outwards).
TestMesh icosphere(int subdivisions);

// Torus around the y axis, centre-circle radius 1, tube radius 0.4, `ringSegments` x `tubeSegments` quads
// (each split in two triangles), shared vertices. Interior: tube of radius 0.2 (half the tube radius, more
// than the polygonisation error 1 - cos(pi / segments) for segments >= 8).
TestMesh torus(int ringSegments, int tubeSegments);

// The glmark2 bunny (/usr/share/glmark2/models/bunny.obj, Debian glmark2-data): NOT closed. Empty if absent.
TestMesh bunny();

// The mesh with every vertex mapped to float(local * scale + offset) (computed in double, rounded once).
TestMesh placed(const TestMesh& mesh, float scale, glm::vec3 offset);

// A Scene (one default diffuse material) for gpu::Renderer.
Scene toScene(const TestMesh& mesh);

// The closed meshes of the suite: icospheres s1, s3, s5 and tori 12x8, 48x24, 192x96.
std::vector<TestMesh> closedMeshes();

struct Placement {
  std::string name;  // "origin", "t=1e5", "embree-verify", "s=1e-4", ...
  float scale;
  glm::vec3 offset;
};
// The translations (scale 1 at 0, 1e3, 1e5, 1e6 on all axes; scale 2 at Embree verify's centre) and the
// scales 1e-4 … 1e4 at the origin.
std::vector<Placement> placements();

}  // namespace ht::accuracy
