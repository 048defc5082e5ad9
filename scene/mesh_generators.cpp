// mesh_generators.cpp - icosphere, box, quad and checker texture generators.
#include "scene/mesh_generators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

namespace ht {
namespace {

// True when every existing vertex carries a normal (resp. texcoord): then new vertices must carry one too.
bool carriesNormals(const Scene& s) { return s.normals.size() == s.positions.size(); }
bool carriesTexcoords(const Scene& s) { return s.texcoords.size() == s.positions.size(); }

std::uint32_t appendVertex(Scene& scene, glm::vec3 position, glm::vec3 normal, glm::vec2 uv) {
  const bool withNormal = carriesNormals(scene), withUv = carriesTexcoords(scene);
  const auto index = static_cast<std::uint32_t>(scene.positions.size());
  scene.positions.push_back(position);
  if (withNormal) scene.normals.push_back(normal);
  if (withUv) scene.texcoords.push_back(uv);
  return index;
}

void appendTriangle(Scene& scene, glm::uvec3 tri, std::uint32_t material) {
  scene.triangles.push_back(tri);
  scene.triangleMaterial.push_back(material);
}

// The 12 vertices and 20 faces of the regular icosahedron: the cyclic permutations of (0, +-1, +-phi),
// phi = (1 + sqrt 5) / 2 (Wikipedia, "Regular icosahedron", Cartesian coordinates). Faces are listed
// counter-clockwise seen from outside (checked by SceneGenerators.IcosphereIsClosedAndOutwardFacing).
struct UnitMesh {
  std::vector<glm::vec3> vertices;  // unit length
  std::vector<glm::uvec3> faces;
};

UnitMesh icosahedron() {
  const float phi = (1.0f + std::sqrt(5.0f)) * 0.5f;
  UnitMesh m;
  m.vertices = {{-1, phi, 0},  {1, phi, 0},  {-1, -phi, 0}, {1, -phi, 0}, {0, -1, phi},  {0, 1, phi},
                {0, -1, -phi}, {0, 1, -phi}, {phi, 0, -1},  {phi, 0, 1},  {-phi, 0, -1}, {-phi, 0, 1}};
  for (glm::vec3& v : m.vertices) v = glm::normalize(v);
  m.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  return m;
}

// One subdivision step: each face (a,b,c) becomes 4 faces through the edge midpoints, pushed to the unit
// sphere. Shared edges share their midpoint vertex (cache keyed by the ordered vertex pair).
UnitMesh subdivide(const UnitMesh& in) {
  UnitMesh out;
  out.vertices = in.vertices;
  out.faces.reserve(in.faces.size() * 4);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
  auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::minmax(a, b);
    auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, 0u);
    if (inserted) {
      it->second = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.push_back(glm::normalize(out.vertices[a] + out.vertices[b]));
    }
    return it->second;
  };
  for (const glm::uvec3& f : in.faces) {
    const std::uint32_t ab = midpoint(f.x, f.y), bc = midpoint(f.y, f.z), ca = midpoint(f.z, f.x);
    out.faces.push_back({f.x, ab, ca});
    out.faces.push_back({f.y, bc, ab});
    out.faces.push_back({f.z, ca, bc});
    out.faces.push_back({ab, bc, ca});
  }
  return out;
}

// Equirectangular texture coordinate of a unit direction: u around +y, v = 0 at the north pole (+y).
glm::vec2 sphereUv(glm::vec3 d) {
  const float pi = 3.14159265358979f;
  const float u = 0.5f + std::atan2(d.x, d.z) / (2.0f * pi);
  const float v = std::acos(glm::clamp(d.y, -1.0f, 1.0f)) / pi;
  return {u, v};
}

}  // namespace

std::uint32_t addMaterial(Scene& scene, Material material) {
  scene.materials.push_back(std::move(material));
  return static_cast<std::uint32_t>(scene.materials.size() - 1);
}

TriangleRange makeIcosphere(Scene& scene, glm::vec3 center, float radius, int subdivisions, std::uint32_t material) {
  if (subdivisions < 0 || subdivisions > 7)
    throw std::invalid_argument("makeIcosphere: subdivisions must be in [0, 7]");
  UnitMesh mesh = icosahedron();
  for (int i = 0; i < subdivisions; ++i) mesh = subdivide(mesh);

  const auto base = static_cast<std::uint32_t>(scene.positions.size());
  for (const glm::vec3& d : mesh.vertices) appendVertex(scene, center + radius * d, d, sphereUv(d));
  const TriangleRange range{scene.triangles.size(), mesh.faces.size()};
  for (const glm::uvec3& f : mesh.faces) appendTriangle(scene, f + glm::uvec3(base), material);
  return range;
}

TriangleRange makeQuad(Scene& scene, glm::vec3 center, glm::vec3 halfU, glm::vec3 halfV, std::uint32_t material) {
  const glm::vec3 n = glm::normalize(glm::cross(halfU, halfV));
  const std::uint32_t a = appendVertex(scene, center - halfU - halfV, n, {0, 0});
  const std::uint32_t b = appendVertex(scene, center + halfU - halfV, n, {1, 0});
  const std::uint32_t c = appendVertex(scene, center + halfU + halfV, n, {1, 1});
  const std::uint32_t d = appendVertex(scene, center - halfU + halfV, n, {0, 1});
  const TriangleRange range{scene.triangles.size(), 2};
  appendTriangle(scene, {a, b, c}, material);
  appendTriangle(scene, {a, c, d}, material);
  return range;
}

TriangleRange makeBox(Scene& scene, glm::vec3 center, glm::vec3 halfExtent, std::uint32_t material) {
  const glm::vec3 h = halfExtent;
  const glm::vec3 ex(h.x, 0, 0), ey(0, h.y, 0), ez(0, 0, h.z);
  // Each face: centre offset and two half-edges whose cross product points outward.
  const std::array<std::array<glm::vec3, 3>, 6> faces{{
      {ex, -ez, ey},
      {-ex, ez, ey},  // +x, -x
      {ey, ex, -ez},
      {-ey, ex, ez},  // +y, -y
      {ez, ex, ey},
      {-ez, -ex, ey},  // +z, -z
  }};
  const TriangleRange range{scene.triangles.size(), 12};
  for (const auto& f : faces) makeQuad(scene, center + f[0], f[1], f[2], material);
  return range;
}

int addCheckerTexture(Scene& scene, std::string name, std::uint32_t size, std::uint32_t cells, glm::vec3 colorA,
                      glm::vec3 colorB) {
  if (size == 0 || cells == 0 || cells > size) throw std::invalid_argument("addCheckerTexture: need 0 < cells <= size");
  Texture t;
  t.name = std::move(name);
  t.width = t.height = size;
  t.texels.resize(std::size_t{size} * size);
  for (std::uint32_t y = 0; y < size; ++y)
    for (std::uint32_t x = 0; x < size; ++x) {
      const bool odd = ((x * cells / size) + (y * cells / size)) % 2 == 1;
      t.texels[std::size_t{y} * size + x] = glm::vec4(odd ? colorB : colorA, 1.0f);
    }
  scene.textures.push_back(std::move(t));
  return static_cast<int>(scene.textures.size() - 1);
}

}  // namespace ht
