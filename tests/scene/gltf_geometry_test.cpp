// gltf_geometry_test.cpp - glTF geometry: index types, topologies, hierarchy transforms, winding, normals,
// texcoords, scene selection, GLB and external buffers. Expected values are worked out by hand in comments.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/gltf_loader.h"
#include "scene/load_scene.h"
#include "scene_test_util.h"

namespace ht {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using test::TempDir;

const std::vector<glm::vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};

void expectVec3Near(glm::vec3 actual, glm::vec3 expected, float tol = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tol);
  EXPECT_NEAR(actual.y, expected.y, tol);
  EXPECT_NEAR(actual.z, expected.z, tol);
}

// A one-node file whose single primitive is `primitive`.
std::string writeSingle(GltfBuilder& b, const TempDir& dir, json primitive, json node = json::object()) {
  node["mesh"] = b.addMesh(primitive);
  b.setScene({b.addNode(node)});
  return b.writeGltf(dir, "single.gltf");
}

class SceneGltfIndexType : public ::testing::TestWithParam<int> {};

TEST_P(SceneGltfIndexType, QuadIndicesOfEveryComponentType) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions(kQuad);
  const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3};
  int indices = -1;
  if (GetParam() == test::kUByte)
    indices = b.addData(std::vector<std::uint8_t>(idx.begin(), idx.end()), test::kUByte, "SCALAR", 1);
  if (GetParam() == test::kUShort)
    indices = b.addData(std::vector<std::uint16_t>(idx.begin(), idx.end()), test::kUShort, "SCALAR", 1);
  if (GetParam() == test::kUInt) indices = b.addData(idx, test::kUInt, "SCALAR", 1);
  const std::string path = writeSingle(b, dir, {{"attributes", {{"POSITION", pos}}}, {"indices", indices}});

  SceneLoadReport report;
  const Scene s = loadGltf(path, &report);
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(s.triangles[1], glm::uvec3(0, 2, 3));
  EXPECT_EQ(s.positions.size(), 4u);
  EXPECT_EQ(report.triangles, 2u);
  ASSERT_EQ(s.materials.size(), 1u);  // the default material for a primitive without one
  EXPECT_EQ(s.triangleMaterial, std::vector<std::uint32_t>({0, 0}));
}

INSTANTIATE_TEST_SUITE_P(U8U16U32, SceneGltfIndexType, ::testing::Values(test::kUByte, test::kUShort, test::kUInt));

TEST(SceneGltf, NonIndexedTriangles) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}, {2, 1, 0}});
  const Scene s = loadGltf(writeSingle(b, dir, {{"attributes", {{"POSITION", pos}}}}));
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(s.triangles[1], glm::uvec3(3, 4, 5));
}

// Spec topology table: strip p_i = {v_i, v_(i+1+i%2), v_(i+2-i%2)}; fan p_i = {v_(i+1), v_(i+2), v_0}.
TEST(SceneGltf, TriangleStripAlternatesWinding) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}});
  const Scene s = loadGltf(writeSingle(b, dir, {{"attributes", {{"POSITION", pos}}}, {"mode", test::kStrip}}));
  ASSERT_EQ(s.triangles.size(), 3u);
  EXPECT_EQ(s.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(s.triangles[1], glm::uvec3(1, 3, 2));
  EXPECT_EQ(s.triangles[2], glm::uvec3(2, 3, 4));
  for (const auto& t : s.triangles) EXPECT_GT(test::geometricNormal(s.positions, t).z, 0.0f);  // all face +z
}

TEST(SceneGltf, TriangleFanAroundFirstVertex) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}});
  const int idx = b.addData(std::vector<std::uint16_t>{0, 1, 2, 3, 4}, test::kUShort, "SCALAR", 1);
  const Scene s =
      loadGltf(writeSingle(b, dir, {{"attributes", {{"POSITION", pos}}}, {"indices", idx}, {"mode", test::kFan}}));
  ASSERT_EQ(s.triangles.size(), 3u);
  EXPECT_EQ(s.triangles[0], glm::uvec3(1, 2, 0));
  EXPECT_EQ(s.triangles[1], glm::uvec3(2, 3, 0));
  EXPECT_EQ(s.triangles[2], glm::uvec3(3, 4, 0));
}

TEST(SceneGltf, PointAndLinePrimitivesAreSkippedAndCounted) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  b.doc["meshes"].push_back({{"primitives",
                              {{{"attributes", {{"POSITION", pos}}}, {"mode", test::kLines}},
                               {{"attributes", {{"POSITION", pos}}}, {"mode", test::kPoints}},
                               {{"attributes", {{"POSITION", pos}}}}}}});
  b.setScene({b.addNode({{"mesh", 0}})});
  SceneLoadReport report;
  const Scene s = loadGltf(b.writeGltf(dir, "modes.gltf"), &report);
  EXPECT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(report.skippedPrimitives, 2u);
  EXPECT_EQ(report.primitives, 1u);
}

// Child: T(1,0,0) R_z(90) S(2). Parent: T(0,0,-5) R_y(90). Local vertex (1,0,0):
//   S -> (2,0,0); R_z(90): (x,y) -> (-y,x) -> (0,2,0); T -> (1,2,0)
//   R_y(90): (x,z) -> (z,-x) -> (0,2,-1); T -> (0,2,-6).
// Local (0,0,1): S -> (0,0,2); R_z -> (0,0,2); T -> (1,0,2); R_y -> (2,0,-1); T -> (2,0,-6).
TEST(SceneGltf, NodeHierarchyComposesParentAndChildTrs) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}});
  const int mesh = b.addMesh({{"attributes", {{"POSITION", pos}}}});
  const double s = std::sqrt(0.5);
  const int child =
      b.addNode({{"mesh", mesh}, {"translation", {1, 0, 0}}, {"rotation", {0, 0, s, s}}, {"scale", {2, 2, 2}}});
  const int parent = b.addNode({{"children", {child}}, {"translation", {0, 0, -5}}, {"rotation", {0, s, 0, s}}});
  b.setScene({parent});
  const Scene sc = loadGltf(b.writeGltf(dir, "tree.gltf"));
  ASSERT_EQ(sc.positions.size(), 3u);
  expectVec3Near(sc.positions[0], {0, 0, -6});  // local origin: T_child (1,0,0); R_y -> (0,0,-1); T -> (0,0,-6)
  expectVec3Near(sc.positions[1], {0, 2, -6});
  expectVec3Near(sc.positions[2], {2, 0, -6});
}

// The parent given as a column-major matrix (translation in elements 12..14) must equal the TRS form.
TEST(SceneGltf, MatrixTransformIsColumnMajor) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  // R_z(90) then translate (10, 20, 30): columns x -> (0,1,0), y -> (-1,0,0), z -> (0,0,1).
  const std::string path = writeSingle(b, dir, {{"attributes", {{"POSITION", pos}}}},
                                       {{"matrix", {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 10, 20, 30, 1}}});
  const Scene s = loadGltf(path);
  expectVec3Near(s.positions[0], {10, 21, 30});
  expectVec3Near(s.positions[1], {9, 20, 30});
  expectVec3Near(s.positions[2], {10, 20, 31});
}

TEST(SceneGltf, NegativeScaleFlipsWindingToKeepFrontFaces) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});  // counter-clockwise seen from +z
  const int nrm = b.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  const std::string path =
      writeSingle(b, dir, {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}}, {{"scale", {-1, 1, 1}}});
  const Scene s = loadGltf(path);
  ASSERT_EQ(s.triangles.size(), 1u);
  expectVec3Near(s.positions[1], {-1, 0, 0});
  // Mirrored in x, the triangle still faces +z: its winding must have been flipped to keep n_geo = +z,
  // consistent with the transformed shading normal M^-T (0,0,1) = (0,0,1).
  EXPECT_GT(test::geometricNormal(s.positions, s.triangles[0]).z, 0.0f);
  expectVec3Near(s.normals[0], {0, 0, 1});
}

// Scale (2,1,1): normals use M^-T = diag(1/2,1,1): (1,1,0)/sqrt2 -> (0.5,1,0)/|.| = (1,2,0)/sqrt5.
// (Transforming like a position would give (2,1,0)/sqrt5 instead.)
TEST(SceneGltf, NormalsTransformByInverseTranspose) {
  TempDir dir;
  GltfBuilder b;
  const float r = std::sqrt(0.5f);
  const int pos = b.addPositions({{0, 0, 0}, {1, -1, 0}, {0, 0, 1}});
  const int nrm = b.addNormals({{r, r, 0}, {r, r, 0}, {r, r, 0}});
  const std::string path =
      writeSingle(b, dir, {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}}, {{"scale", {2, 1, 1}}});
  const Scene s = loadGltf(path);
  ASSERT_EQ(s.normals.size(), 3u);
  const float k = 1.0f / std::sqrt(5.0f);
  for (const glm::vec3& n : s.normals) expectVec3Near(n, {k, 2 * k, 0});
  // The transformed normal stays perpendicular to the transformed surface (edge p1 - p0).
  EXPECT_NEAR(glm::dot(s.normals[0], s.positions[1] - s.positions[0]), 0.0f, 1e-5f);
}

TEST(SceneGltf, PrimitivesWithoutNormalsGetFlatNormalsWhenOthersHaveThem) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int nrm = b.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  const int posB = b.addPositions({{0, 0, 0}, {0, 0, 1}, {1, 0, 0}});  // faces +y
  b.doc["meshes"].push_back(
      {{"primitives",
        {{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}}, {{"attributes", {{"POSITION", posB}}}}}}});
  b.setScene({b.addNode({{"mesh", 0}})});
  const Scene s = loadGltf(b.writeGltf(dir, "mixed.gltf"));
  ASSERT_EQ(s.normals.size(), s.positions.size());
  ASSERT_EQ(s.triangles.size(), 2u);
  for (int k = 0; k < 3; ++k) expectVec3Near(s.normals[s.triangles[1][k]], {0, 1, 0});
}

TEST(SceneGltf, NormalizedIntegerTexcoords) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int uv =
      b.addData(std::vector<std::uint16_t>{0, 65535, 32768, 0, 65535, 65535}, test::kUShort, "VEC2", 2, true);
  const Scene s = loadGltf(writeSingle(b, dir, {{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}}));
  ASSERT_EQ(s.texcoords.size(), 3u);
  EXPECT_FLOAT_EQ(s.texcoords[0].x, 0.0f);
  EXPECT_FLOAT_EQ(s.texcoords[0].y, 1.0f);
  EXPECT_FLOAT_EQ(s.texcoords[1].x, 32768.0f / 65535.0f);  // spec: c / 65535
  EXPECT_FLOAT_EQ(s.texcoords[2].y, 1.0f);
}

TEST(SceneGltf, FloatTexcoordsAndUnsignedByteTexcoords) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int uv = b.addData(std::vector<std::uint8_t>{0, 255, 51, 0, 255, 255, 0, 0}, test::kUByte, "VEC2", 2, true);
  b.doc["accessors"][uv]["count"] = 3;  // the 8 bytes hold 3 VEC2 elements + 2 padding bytes
  const Scene s = loadGltf(writeSingle(b, dir, {{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}}));
  ASSERT_EQ(s.texcoords.size(), 3u);
  EXPECT_FLOAT_EQ(s.texcoords[1].x, 51.0f / 255.0f);  // spec: c / 255
  EXPECT_FLOAT_EQ(s.texcoords[0].y, 1.0f);
}

TEST(SceneGltf, NonFinitePositionsAreKeptAndCounted) {
  TempDir dir;
  GltfBuilder b;
  const float nan = std::nanf("");
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {nan, 0, 0}, {1, 1, 1}, {INFINITY, 0, 0}});
  SceneLoadReport report;
  const Scene s = loadGltf(writeSingle(b, dir, {{"attributes", {{"POSITION", pos}}}}), &report);
  EXPECT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(report.nonFiniteVertices, 2u);
  EXPECT_TRUE(std::isnan(s.positions[3].x));
  EXPECT_EQ(s.bounds().hi.x, 1.0f);  // bounds ignore the non-finite vertices
}

// Two scenes: `scene` picks one; without `scene`, scene 0; without scenes, every root node.
TEST(SceneGltf, DefaultSceneSelection) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int mesh = b.addMesh({{"attributes", {{"POSITION", pos}}}});
  b.addNode({{"mesh", mesh}, {"translation", {10, 0, 0}}});                     // node 0
  b.addNode({{"mesh", mesh}, {"translation", {20, 0, 0}}});                     // node 1
  b.addNode({{"mesh", mesh}, {"translation", {30, 0, 0}}, {"children", {1}}});  // node 2, parent of 1
  b.doc["scenes"] = json::array({{{"nodes", {0}}}, {{"nodes", {2}}}});

  b.doc["scene"] = 1;
  const Scene s1 = loadGltf(b.writeGltf(dir, "scene1.gltf"));
  ASSERT_EQ(s1.triangles.size(), 2u);  // node 2 and its child node 1 at 30 + 20
  EXPECT_FLOAT_EQ(s1.positions[0].x, 30.0f);
  EXPECT_FLOAT_EQ(s1.positions[3].x, 50.0f);

  b.doc.erase("scene");
  const Scene s0 = loadGltf(b.writeGltf(dir, "scene0.gltf"));
  ASSERT_EQ(s0.triangles.size(), 1u);
  EXPECT_FLOAT_EQ(s0.positions[0].x, 10.0f);

  b.doc.erase("scenes");
  const Scene all = loadGltf(b.writeGltf(dir, "roots.gltf"));
  EXPECT_EQ(all.triangles.size(), 3u);  // roots 0 and 2, plus 2's child 1
}

TEST(SceneGltf, SameMeshInstancedByTwoNodes) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int mesh = b.addMesh({{"attributes", {{"POSITION", pos}}}});
  b.setScene({b.addNode({{"mesh", mesh}}), b.addNode({{"mesh", mesh}, {"translation", {0, 0, 5}}})});
  const Scene s = loadGltf(b.writeGltf(dir, "inst.gltf"));
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_FLOAT_EQ(s.positions[s.triangles[1].x].z, 5.0f);
}

TEST(SceneGltf, GlbAssembledFromBytesLoads) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions(kQuad);
  const int idx = b.addData(std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3}, test::kUShort, "SCALAR", 1);
  b.setScene({b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
  const Scene s = loadScene(b.writeGlb(dir, "quad.GLB"));  // extension is case-insensitive
  ASSERT_EQ(s.triangles.size(), 2u);
  expectVec3Near(s.positions[2], {1, 1, 0});
}

TEST(SceneGltf, ExternalBufferNextToTheGltf) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions(kQuad);
  const int idx = b.addData(std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}, test::kUInt, "SCALAR", 1);
  b.setScene({b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
  const Scene s = loadScene(b.writeGltfExternal(dir, "ext.gltf", "ext.bin"));
  EXPECT_EQ(s.triangles.size(), 2u);
}

TEST(SceneGltf, SparseAccessorOverridesBaseValues) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int sparseIdx = b.addBufferView(std::string("\x02\x00", 2));
  std::vector<float> v = {0, 7, 0};
  const int sparseVal = b.addBufferView(std::string(reinterpret_cast<const char*>(v.data()), 12));
  b.doc["accessors"][pos]["sparse"] = {{"count", 1},
                                       {"indices", {{"bufferView", sparseIdx}, {"componentType", test::kUShort}}},
                                       {"values", {{"bufferView", sparseVal}}}};
  const Scene s = loadGltf(writeSingle(b, dir, {{"attributes", {{"POSITION", pos}}}}));
  expectVec3Near(s.positions[2], {0, 7, 0});
  expectVec3Near(s.positions[1], {1, 0, 0});
}

// KHR_mesh_quantization: integer positions without `normalized` are plain integer values.
TEST(SceneGltf, QuantizedShortPositions) {
  TempDir dir;
  GltfBuilder b;
  b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  const int pos = b.addData(std::vector<std::int16_t>{0, 0, 0, 0, 100, 0, 0, 0, -3, 7, 0, 0}, test::kShort, "VEC3", 3);
  b.doc["bufferViews"][0]["byteStride"] = 8;  // 6-byte elements padded to 4-byte alignment
  b.doc["accessors"][pos]["count"] = 3;
  const Scene s = loadGltf(writeSingle(b, dir, {{"attributes", {{"POSITION", pos}}}}));
  ASSERT_EQ(s.positions.size(), 3u);
  expectVec3Near(s.positions[1], {100, 0, 0});  // element 1 = shorts 4..6 (stride 8 bytes = 4 shorts)
  expectVec3Near(s.positions[2], {-3, 7, 0});
}

}  // namespace
}  // namespace ht
