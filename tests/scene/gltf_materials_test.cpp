// gltf_materials_test.cpp - glTF materials (PBR factors and KHR extensions -> Material::kind()), base-colour
// textures decoded to linear, and KHR_lights_punctual placement.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/gltf_loader.h"
#include "scene_test_util.h"

namespace ht {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using test::TempDir;

// A file with one triangle per material, triangle i using material i.
Scene loadWithMaterials(const json& materials, GltfBuilder& b, const TempDir& dir, SceneLoadReport* report = nullptr) {
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  json prims = json::array();
  for (std::size_t i = 0; i < materials.size(); ++i)
    prims.push_back({{"attributes", {{"POSITION", pos}}}, {"material", i}});
  b.doc["materials"] = materials;
  b.doc["meshes"].push_back({{"primitives", prims}});
  b.setScene({b.addNode({{"mesh", 0}})});
  return loadGltf(b.writeGltf(dir, "materials.gltf"), report);
}

TEST(SceneGltfMaterials, FactorsAndExtensionsMapToMaterialKinds) {
  TempDir dir;
  GltfBuilder b;
  const json materials = json::array({
      {{"name", "paint"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.4, 0.6, 1.0}}, {"metallicFactor", 0.2}}}},
      {{"name", "chrome"}, {"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 0.1}}}},
      {{"name", "brushed"}, {"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 0.6}}}},
      {{"name", "water"},
       {"extensions",
        {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}, {"KHR_materials_ior", {{"ior", 1.33}}}}}},
      {{"name", "lamp"},
       {"emissiveFactor", {1.0, 0.5, 0.25}},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}},
  });
  const Scene s = loadWithMaterials(materials, b, dir);
  ASSERT_EQ(s.materials.size(), 5u);
  EXPECT_EQ(s.materials[0].name, "paint");
  EXPECT_FLOAT_EQ(s.materials[0].baseColor.y, 0.4f);
  EXPECT_FLOAT_EQ(s.materials[0].metallic, 0.2f);
  EXPECT_FLOAT_EQ(s.materials[0].roughness, 1.0f);  // glTF default roughnessFactor
  EXPECT_EQ(s.materials[0].kind(), MaterialKind::Diffuse);
  EXPECT_EQ(s.materials[1].kind(), MaterialKind::Mirror);
  EXPECT_EQ(s.materials[2].kind(), MaterialKind::Diffuse);  // rough metal is not a mirror
  EXPECT_EQ(s.materials[3].kind(), MaterialKind::Glass);
  EXPECT_FLOAT_EQ(s.materials[3].transmission, 1.0f);
  EXPECT_FLOAT_EQ(s.materials[3].ior, 1.33f);
  EXPECT_FLOAT_EQ(s.materials[4].emissive.x, 4.0f);  // emissiveFactor * emissiveStrength
  EXPECT_FLOAT_EQ(s.materials[4].emissive.z, 1.0f);
  EXPECT_FLOAT_EQ(s.materials[1].ior, 1.5f);  // KHR_materials_ior default
  EXPECT_EQ(s.triangleMaterial, std::vector<std::uint32_t>({0, 1, 2, 3, 4}));
  const SceneFeatures f = s.features();
  EXPECT_TRUE(f.mirrors && f.glass && f.emissive);
  EXPECT_FALSE(f.lights || f.textures);
}

// 2x1 RGBA texture, sRGB bytes 0/128/255/10 -> linear by the IEC 61966-2-1 curve:
// 128/255 = 0.50196: ((0.50196 + 0.055) / 1.055)^2.4 = 0.21586; 10/255 / 12.92 = 0.0030353; alpha stays linear.
TEST(SceneGltfMaterials, BaseColorTextureIsDecodedToLinear) {
  TempDir dir;
  GltfBuilder b;
  const std::string png = test::encodePng(2, 1, 4, {0, 128, 255, 128, 10, 255, 0, 255});
  b.doc["images"] = json::array({{{"bufferView", b.addBufferView(png)}, {"mimeType", "image/png"}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  const json materials = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  const Scene s = loadWithMaterials(materials, b, dir);
  ASSERT_EQ(s.textures.size(), 1u);
  const Texture& t = s.textures[0];
  ASSERT_EQ(t.width, 2u);
  ASSERT_EQ(t.height, 1u);
  EXPECT_EQ(s.materials[0].baseColorTexture, 0);
  EXPECT_FLOAT_EQ(t.texels[0].x, 0.0f);
  EXPECT_NEAR(t.texels[0].y, 0.21586f, 1e-5f);
  EXPECT_FLOAT_EQ(t.texels[0].z, 1.0f);
  EXPECT_NEAR(t.texels[0].w, 128.0f / 255.0f, 1e-6f);  // alpha is not sRGB-decoded
  EXPECT_NEAR(t.texels[1].x, 0.0030353f, 1e-6f);
  EXPECT_FLOAT_EQ(t.texels[1].w, 1.0f);
  EXPECT_TRUE(s.features().textures);
}

TEST(SceneGltfMaterials, RgbPngFromDataUriGetsOpaqueAlpha) {
  TempDir dir;
  GltfBuilder b;
  const std::string png = test::encodePng(1, 2, 3, {255, 0, 0, 0, 255, 0});  // top red, bottom green
  b.doc["images"] = json::array({{{"uri", "data:image/png;base64," + test::base64(png)}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  const json materials = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  const Scene s = loadWithMaterials(materials, b, dir);
  ASSERT_EQ(s.textures.size(), 1u);
  ASSERT_EQ(s.textures[0].texels.size(), 2u);
  EXPECT_EQ(s.textures[0].texels[0], glm::vec4(1, 0, 0, 1));  // row 0 = image top
  EXPECT_EQ(s.textures[0].texels[1], glm::vec4(0, 1, 0, 1));
}

// A node at T(10,0,0) with a child at T(1,2,3) R_x(90). R_x(90) maps (x,y,z) -> (x, -z, y), so the light's
// local -Z (0,0,-1) becomes (0,1,0) and its origin lands at (11,2,3).
TEST(SceneGltfMaterials, PunctualLightsTakePositionAndDirectionFromNodes) {
  TempDir dir;
  GltfBuilder b;
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({
      {{"type", "spot"},
       {"color", {1.0, 0.5, 0.25}},
       {"intensity", 20.0},
       {"range", 7.0},
       {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}},
      {{"type", "directional"}, {"intensity", 3.0}},
      {{"type", "point"}},
  });
  const double s = std::sqrt(0.5);
  const int spot = b.addNode({{"translation", {1, 2, 3}},
                              {"rotation", {s, 0, 0, s}},
                              {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  const int parent = b.addNode({{"translation", {10, 0, 0}}, {"children", {spot}}});
  const int sun = b.addNode({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});  // identity: shines along -Z
  const int bulb = b.addNode({{"translation", {0, 5, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int geom = b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", pos}}}})}});
  b.setScene({parent, sun, bulb, geom});
  SceneLoadReport report;
  const Scene sc = loadGltf(b.writeGltf(dir, "lights.gltf"), &report);
  ASSERT_EQ(sc.lights.size(), 3u);
  EXPECT_EQ(report.lights, 3u);
  const Light& l0 = sc.lights[0];
  EXPECT_EQ(l0.type, Light::Type::Spot);
  EXPECT_NEAR(l0.position.x, 11.0f, 1e-5f);
  EXPECT_NEAR(l0.position.y, 2.0f, 1e-5f);
  EXPECT_NEAR(l0.position.z, 3.0f, 1e-5f);
  EXPECT_NEAR(l0.direction.x, 0.0f, 1e-6f);
  EXPECT_NEAR(l0.direction.y, 1.0f, 1e-6f);
  EXPECT_NEAR(l0.direction.z, 0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(l0.intensity, 20.0f);
  EXPECT_FLOAT_EQ(l0.range, 7.0f);
  EXPECT_FLOAT_EQ(l0.color.y, 0.5f);
  EXPECT_FLOAT_EQ(l0.innerConeAngle, 0.1f);
  EXPECT_FLOAT_EQ(l0.outerConeAngle, 0.5f);
  EXPECT_EQ(sc.lights[1].type, Light::Type::Directional);
  EXPECT_EQ(sc.lights[1].direction, glm::vec3(0, 0, -1));
  EXPECT_EQ(sc.lights[2].type, Light::Type::Point);
  EXPECT_EQ(sc.lights[2].position, glm::vec3(0, 5, 0));
  EXPECT_TRUE(sc.features().lights);
}

}  // namespace
}  // namespace ht
