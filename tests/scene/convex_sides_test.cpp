// convex_sides_test.cpp - which sides of a node a ray leaves without meeting it again (scene/convex_sides.h): the
// built-in solids are convex with their winding facing out, reversed winding turns the outside round, a flat node is
// outside on both sides, a dent, a shared vertex or an oversized node is not convex, and the marks survive moves and
// mesh sharing in glTF files.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "scene/builtin_scenes.h"
#include "scene/convex_sides.h"
#include "scene/gltf_loader.h"
#include "scene/mesh_generators.h"
#include "scene/scene_edits.h"
#include "scene_test_util.h"

namespace ht {
namespace {

// A scene of one node made by `add` (a mesh generator).
template <class Add>
Scene oneNode(Add add) {
  Scene s;
  s.materials.push_back(Material{"m"});
  SceneNode node;
  node.name = "n";
  add(s);
  node.vertexCount = static_cast<std::uint32_t>(s.positions.size());
  node.triangleCount = static_cast<std::uint32_t>(s.triangles.size());
  s.nodes.push_back(node);
  return s;
}

Scene sphere(int subdivisions = 2) {
  return oneNode([&](Scene& s) { makeIcosphere(s, {0.3f, -0.2f, 0.5f}, 0.7f, subdivisions, 0); });
}

TEST(ConvexSides, BuiltinSolidsAreConvexWithTheirWindingOutsideAndTheRoomIsNot) {
  const Scene showcase = makeBuiltinScene("showcase");
  ASSERT_EQ(showcase.nodes.size(), 6u);
  for (const SceneNode& node : showcase.nodes) {
    // The floor and back wall meet in an inner corner: outside on their backs (below the floor, behind the wall).
    const std::uint8_t expected = node.name == "room" ? kConvexBack : kConvexFront;
    EXPECT_EQ(convexSides(showcase, node), expected) << node.name;
  }
  EXPECT_EQ(convexSides(sphere(), sphere().nodes[0]), kConvexFront);
  const Scene box = oneNode([](Scene& s) { makeBox(s, {1.0f, 2.0f, 3.0f}, {0.5f, 0.25f, 2.0f}, 0); });
  EXPECT_EQ(convexSides(box, box.nodes[0]), kConvexFront);  // coplanar pairs of triangles on each face
}

// The built-in scenes set their marks by construction (no plane tests at every load): they must be what the test
// finds, where the test runs (builtin:sphere's 20,480 triangles are over kMaxConvexPlaneTests).
TEST(ConvexSides, BuiltinMarksAreWhatTheTestFinds) {
  for (const std::string& name : builtinSceneNames()) {
    const Scene s = loadScene(name);  // ("builtin:NAME")
    for (const SceneNode& node : s.nodes) {
      if (std::uint64_t{node.triangleCount} * node.vertexCount > kMaxConvexPlaneTests) continue;
      EXPECT_EQ(node.convexSides, convexSides(s, node)) << name << " " << node.name;
    }
  }
}

TEST(ConvexSides, ReversedWindingPutsTheOutsideOnTheBackAndAFlatNodeHasItOnBothSides) {
  Scene s = sphere();
  for (glm::uvec3& t : s.triangles) std::swap(t.y, t.z);
  EXPECT_EQ(convexSides(s, s.nodes[0]), kConvexBack);
  const Scene quad = oneNode([](Scene& q) {
    makeQuad(q, {0.0f, 1.0f, 0.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 3.0f}, 0);
  });
  EXPECT_EQ(convexSides(quad, quad.nodes[0]), kConvexFront | kConvexBack);
}

TEST(ConvexSides, ADentASharedVertexOrTooManyPlaneTestsIsNotConvex) {
  Scene dented = sphere();
  const glm::vec3 centre(0.3f, -0.2f, 0.5f);
  dented.positions[7] = centre + 0.8f * (dented.positions[7] - centre);  // below its neighbours' planes
  EXPECT_EQ(convexSides(dented, dented.nodes[0]), 0);
  Scene bump = sphere();
  bump.positions[7] = centre + 1.2f * (bump.positions[7] - centre);  // above them: convex from the inside neither
  EXPECT_EQ(convexSides(bump, bump.nodes[0]), 0);
  Scene shared = sphere();
  shared.nodes[0].vertexCount -= 1;  // the last vertex is no longer the node's own
  EXPECT_EQ(convexSides(shared, shared.nodes[0]), 0);
  const Scene big = sphere(6);  // 81,920 triangles x 40,962 vertices: over kMaxConvexPlaneTests
  ASSERT_GT(std::uint64_t{big.nodes[0].triangleCount} * big.nodes[0].vertexCount, kMaxConvexPlaneTests);
  EXPECT_EQ(convexSides(big, big.nodes[0]), 0);
}

TEST(ConvexSides, AScenePastItsBudgetOfPlaneTestsLeavesTheRestUnmarked) {
  Scene s;
  s.materials.push_back(Material{"m"});
  const auto add = [&s](auto generate) {
    SceneNode node;
    node.name = "n" + std::to_string(s.nodes.size());
    node.firstVertex = static_cast<std::uint32_t>(s.positions.size());
    node.firstTriangle = static_cast<std::uint32_t>(s.triangles.size());
    generate();
    node.vertexCount = static_cast<std::uint32_t>(s.positions.size()) - node.firstVertex;
    node.triangleCount = static_cast<std::uint32_t>(s.triangles.size()) - node.firstTriangle;
    s.nodes.push_back(node);
  };
  // Eleven spheres of 5,120 triangles x 2,562 vertices (13.1 M plane tests each): ten fit in the scene's budget.
  for (int k = 0; k < 11; ++k) add([&] { makeIcosphere(s, {2.0f * float(k), 0.0f, 0.0f}, 0.5f, 4, 0); });
  add([&] { makeBox(s, {0.0f, 3.0f, 0.0f}, glm::vec3(0.5f), 0); });  // 96 tests: still fits
  ASSERT_GT(11 * std::uint64_t{s.nodes[0].triangleCount} * s.nodes[0].vertexCount, kMaxConvexPlaneTestsPerScene);
  EXPECT_EQ(markConvexNodes(s), 1u);
  for (int k = 0; k < 10; ++k) EXPECT_EQ(s.nodes[static_cast<std::size_t>(k)].convexSides, kConvexFront) << k;
  EXPECT_EQ(s.nodes[10].convexSides, 0);
  EXPECT_EQ(s.nodes[11].convexSides, kConvexFront);
}

TEST(ConvexSides, MovesKeepTheMarksTrue) {
  Scene s = makeBuiltinScene("showcase");
  const glm::dmat4 mirrored = glm::dmat4(glm::dvec4(-1.5, 0, 0, 0), glm::dvec4(0, 0.5, 0.2, 0), glm::dvec4(0, 0, 2, 0),
                                         glm::dvec4(0.1, 0.2, -0.3, 1));
  for (const char* name : {"green-sphere", "red-box"}) setNodeWorldMatrix(s, name, mirrored);
  for (const SceneNode& node : s.nodes) EXPECT_EQ(node.convexSides, convexSides(s, node)) << node.name;
}

TEST(ConvexSides, NodesSharingAMeshGetTheirOwnOutsideMirroredOrNot) {
  test::GltfBuilder b;
  // A tetrahedron wound outwards.
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  const int idx = b.addData(std::vector<std::uint16_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}, test::kUShort, "SCALAR", 1);
  const int mesh = b.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  b.setScene({b.addNode({{"mesh", mesh}, {"name", "plain"}}),
              b.addNode({{"mesh", mesh}, {"name", "mirrored"}, {"scale", {-1, 1, 1}}, {"translation", {3, 0, 0}}}),
              b.addNode({{"mesh", mesh}, {"name", "stretched"}, {"scale", {4, 0.5, 2}}})});
  const test::TempDir dir;
  const Scene s = loadGltf(b.writeGltf(dir, "tetra.gltf"));
  ASSERT_EQ(s.nodes.size(), 3u);
  EXPECT_EQ(s.nodes[0].convexSides, kConvexFront);
  for (const SceneNode& node : s.nodes) {
    EXPECT_NE(node.convexSides, 0) << node.name;
    EXPECT_EQ(node.convexSides, convexSides(s, node)) << node.name;  // the shared result, checked node by node
  }
}

}  // namespace
}  // namespace ht
