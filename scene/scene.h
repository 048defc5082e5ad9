// scene.h - the renderer's scene: a flattened, world-space triangle soup with materials, textures and
// punctual lights. Loaders (glTF, OBJ/OFF, built-in procedural scenes) all produce this one type.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/bounds3.h"

namespace ht {

// Whitted-style material classes the shader distinguishes (derived from the glTF PBR parameters).
enum class MaterialKind : std::uint32_t { Diffuse = 0, Mirror = 1, Glass = 2 };

struct Material {
  std::string name;
  glm::vec3 baseColor{0.8f};  // linear RGB (glTF baseColorFactor.rgb)
  int baseColorTexture = -1;  // index into Scene::textures, -1 = none
  glm::vec3 emissive{0.0f};   // linear RGB radiance (emissiveFactor * KHR_materials_emissive_strength)
  float metallic = 0.0f;      // glTF metallicFactor
  float roughness = 1.0f;     // glTF roughnessFactor
  float transmission = 0.0f;  // KHR_materials_transmission
  float ior = 1.5f;           // KHR_materials_ior
  // Mirror: metallic >= 0.5 and roughness <= 0.25. Glass: transmission >= 0.5. Everything else: Diffuse.
  MaterialKind kind() const {
    if (transmission >= 0.5f) return MaterialKind::Glass;
    if (metallic >= 0.5f && roughness <= 0.25f) return MaterialKind::Mirror;
    return MaterialKind::Diffuse;
  }
};

struct Texture {
  std::string name;
  std::uint32_t width = 0, height = 0;
  std::vector<glm::vec4> texels;  // linear RGBA (sRGB decoded), row 0 = image top = glTF uv v = 0
};

struct Light {  // KHR_lights_punctual
  enum class Type : std::uint32_t { Point = 0, Spot = 1, Directional = 2 };
  Type type = Type::Point;
  glm::vec3 position{0.0f};                // world space (Point, Spot)
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // world-space direction the light travels (Spot, Directional), unit
  glm::vec3 color{1.0f};                   // linear RGB
  float intensity = 1.0f;                  // candela (Point, Spot) or lux (Directional), as in glTF
  float range = 0.0f;                      // 0 = infinite
  float innerConeAngle = 0.0f, outerConeAngle = 0.785398f;  // radians (Spot)
};

// A named piece of the soup that can be moved after loading (holotraced UpdateScene): a glTF node instance's
// primitives, or one object of a built-in scene. Its vertices belong to it alone (loaders copy per instance).
struct SceneNode {
  std::string name;  // glTF node name ("node<i>" if unnamed), built-in object name
  std::uint32_t firstVertex = 0, vertexCount = 0;
  std::uint32_t firstTriangle = 0, triangleCount = 0;
  glm::dmat4 world{1.0};         // the world matrix the vertices are currently transformed by (identity for
                                 // built-in objects, whose vertices are generated in world space)
  std::int32_t mesh = -1;        // the glTF mesh this node instances (nodes with the same mesh have the same
                                 // triangles in the same order under different matrices); -1 = its own
  std::uint8_t convexSides = 0;  // the sides of its triangles a ray leaves without meeting it again
                                 // (kConvexFront | kConvexBack, scene/convex_sides.h; set by the loaders)
};

// A contiguous range of Scene::triangles placed by one node (or, with node = -1, triangles that belong to no
// node), for two-level acceleration structures (docs/REUSE.md §3). sceneInstances covers every triangle once,
// in triangle order.
struct SceneInstance {
  std::uint32_t firstTriangle = 0, triangleCount = 0;
  std::int32_t mesh = -1;  // SceneNode::mesh, -1 for the rest
  std::int32_t node = -1;  // index into Scene::nodes, -1 for triangles outside every node
};

struct SceneFeatures {
  bool lights = false, mirrors = false, glass = false, textures = false, emissive = false;
};

struct Scene {
  std::string name;                             // file path or "builtin:NAME"
  std::vector<glm::vec3> positions;             // world space
  std::vector<glm::vec3> normals;               // per vertex, world space, unit; empty = use face normals
  std::vector<glm::vec2> texcoords;             // per vertex; empty = none
  std::vector<glm::uvec3> triangles;            // vertex indices
  std::vector<std::uint32_t> triangleMaterial;  // per triangle, index into materials
  std::vector<Material> materials;              // never empty after loading (a default material is added)
  std::vector<Texture> textures;
  std::vector<Light> lights;
  std::vector<SceneNode> nodes;               // movable pieces; may be empty (OBJ/OFF meshes)
  glm::vec3 background{0.05f, 0.06f, 0.08f};  // radiance of rays that leave the scene (linear RGB)
  glm::vec3 ambient{0.15f};                   // constant ambient irradiance term applied to diffuse surfaces

  Bounds3 bounds() const;
  std::vector<SceneInstance> instances() const;
  SceneFeatures features() const;
  std::size_t triangleCount() const { return triangles.size(); }
};

// Loads "builtin:NAME", a .gltf/.glb (tinygltf), or a .obj/.off mesh (positions only). Throws SceneError
// naming the file and what is wrong.
Scene loadScene(const std::string& spec);
std::vector<std::string> builtinSceneNames();

}  // namespace ht
