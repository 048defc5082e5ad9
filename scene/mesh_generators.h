// mesh_generators.h - procedural triangle meshes appended to a Scene (built-in scenes, tests).
//
// Every generator appends world-space vertices and counter-clockwise (outward-facing, glTF convention)
// triangles tagged with `material`, and returns the range of triangles it added. Per-vertex normals and
// texcoords are written when the Scene already carries them for every vertex (always true for a Scene
// built only from generators), so the Scene's arrays stay the same length.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace ht {

struct TriangleRange {
  std::size_t first = 0;  // index of the first triangle added
  std::size_t count = 0;  // number of triangles added
};

// Appends `material` to scene.materials and returns its index.
std::uint32_t addMaterial(Scene& scene, Material material);

// Unit-direction icosphere: the icosahedron subdivided `subdivisions` times (each step splits every
// triangle into 4), vertices pushed onto the sphere. 20 * 4^subdivisions triangles; subdivisions in [0, 7].
TriangleRange makeIcosphere(Scene& scene, glm::vec3 center, float radius, int subdivisions, std::uint32_t material);

// Axis-aligned box with the given centre and half extents; 12 triangles, flat normals, uv 0..1 per face.
TriangleRange makeBox(Scene& scene, glm::vec3 center, glm::vec3 halfExtent, std::uint32_t material);

// Parallelogram with corners center +- halfU +- halfV; 2 triangles facing normalize(cross(halfU, halfV)).
// uv = (0,0) at center-halfU-halfV ... (1,1) at center+halfU+halfV.
TriangleRange makeQuad(Scene& scene, glm::vec3 center, glm::vec3 halfU, glm::vec3 halfV, std::uint32_t material);

// A size x size checkerboard texture with `cells` x `cells` squares of two linear colours; returns its
// index in scene.textures.
int addCheckerTexture(Scene& scene, std::string name, std::uint32_t size, std::uint32_t cells, glm::vec3 colorA,
                      glm::vec3 colorB);

}  // namespace ht
