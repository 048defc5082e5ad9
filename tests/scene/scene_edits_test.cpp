// scene_edits_test.cpp - moving nodes and editing lights after loading (holotraced UpdateScene): a node moved to a
// new world matrix lands where loading it with that matrix puts it (the independent reference: the loader itself
// on an edited file), handedness changes keep front faces, other nodes are untouched, bad edits change nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "scene/gltf_loader.h"
#include "scene/load_scene.h"
#include "scene/scene_edits.h"
#include "scene_test_util.h"

namespace ht {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using test::TempDir;

// Two nodes sharing one mesh: "left" translated by (-2, 0, 0), "right" by `rightTrs` (a glTF node object).
std::string twoNodeFile(const TempDir& dir, const std::string& name, const json& rightTrs) {
  GltfBuilder b;
  const float r = std::sqrt(0.5f);
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int nrm = b.addNormals({{r, 0, r}, {0, 0, 1}, {0, r, r}});
  const int mesh = b.addMesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}});
  json right = rightTrs;
  right["mesh"] = mesh;
  right["name"] = "right";
  const int left = b.addNode({{"mesh", mesh}, {"name", "left"}, {"translation", {-2, 0, 0}}});
  b.setScene({left, b.addNode(right)});
  return b.writeGltf(dir, name);
}

glm::dmat4 columnMajor(const std::vector<double>& m) {
  glm::dmat4 out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c][r] = m[static_cast<std::size_t>(c * 4 + r)];
  return out;
}

void expectSameGeometry(const Scene& a, const Scene& b, float tol) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles, b.triangles);
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_LT(glm::length(a.positions[i] - b.positions[i]), tol) << "vertex " << i;
    EXPECT_LT(glm::length(a.normals[i] - b.normals[i]), tol) << "normal " << i;
  }
}

TEST(SceneEdits, GltfNodesAreRecordedWithTheirRanges) {
  TempDir dir;
  const Scene s = loadGltf(twoNodeFile(dir, "a.gltf", {{"translation", {3, 0, 0}}}));
  ASSERT_EQ(s.nodes.size(), 2u);
  EXPECT_EQ(s.nodes[0].name, "left");
  EXPECT_EQ(s.nodes[1].name, "right");
  EXPECT_EQ(s.nodes[1].firstVertex, 3u);
  EXPECT_EQ(s.nodes[1].vertexCount, 3u);
  EXPECT_EQ(s.nodes[1].firstTriangle, 1u);
  EXPECT_EQ(s.nodes[1].world[3], glm::dvec4(3, 0, 0, 1));
}

// Moving "right" from translation (3, 0, 0) to a rotated, scaled, translated matrix equals loading the file written
// with that matrix; "left" does not move.
TEST(SceneEdits, NodesRecordTheMeshTheyInstanceAndInstancesCoverEveryTriangle) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int shared = b.addMesh({{"attributes", {{"POSITION", pos}}}});
  const int other = b.addMesh({{"attributes", {{"POSITION", pos}}}});
  b.setScene({b.addNode({{"mesh", shared}, {"name", "a"}}), b.addNode({{"name", "empty"}}),
              b.addNode({{"mesh", other}, {"name", "b"}, {"translation", {0, 0, 2}}}),
              b.addNode({{"mesh", shared}, {"name", "c"}, {"translation", {0, 0, 5}}})});
  const Scene s = loadGltf(b.writeGltf(dir, "inst.gltf"));
  ASSERT_EQ(s.nodes.size(), 3u);  // the node without a mesh places nothing
  EXPECT_EQ(s.nodes[0].mesh, shared);
  EXPECT_EQ(s.nodes[1].mesh, other);
  EXPECT_EQ(s.nodes[2].mesh, shared);
  const std::vector<SceneInstance> inst = s.instances();
  ASSERT_EQ(inst.size(), 3u);
  for (std::size_t i = 0; i < inst.size(); ++i) {
    EXPECT_EQ(inst[i].node, static_cast<int>(i));
    EXPECT_EQ(inst[i].mesh, s.nodes[i].mesh);
    EXPECT_EQ(inst[i].firstTriangle, i);
    EXPECT_EQ(inst[i].triangleCount, 1u);
  }
}

TEST(SceneEdits, InstancesFillTheGapsBetweenNodesWithNodelessRanges) {
  Scene s;
  s.triangles.resize(10, glm::uvec3(0));
  SceneNode n;
  n.firstTriangle = 3;
  n.triangleCount = 4;
  n.mesh = 7;
  s.nodes.push_back(n);
  const std::vector<SceneInstance> inst = s.instances();
  ASSERT_EQ(inst.size(), 3u);
  EXPECT_EQ(inst[0].firstTriangle, 0u);
  EXPECT_EQ(inst[0].triangleCount, 3u);
  EXPECT_EQ(inst[0].node, -1);
  EXPECT_EQ(inst[1].node, 0);
  EXPECT_EQ(inst[1].mesh, 7);
  EXPECT_EQ(inst[2].firstTriangle, 7u);
  EXPECT_EQ(inst[2].triangleCount, 3u);
  EXPECT_EQ(inst[2].mesh, -1);
}

TEST(SceneEdits, MovedNodeEqualsLoadingWithTheNewMatrix) {
  TempDir dir;
  const std::vector<double> m = {0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 2, 0, 10, 20, 30, 1};  // R_z(90) * 2, then T
  Scene moved = loadGltf(twoNodeFile(dir, "a.gltf", {{"translation", {3, 0, 0}}}));
  setNodeWorldMatrix(moved, "right", columnMajor(m));
  const Scene expected = loadGltf(twoNodeFile(dir, "b.gltf", {{"matrix", m}}));
  expectSameGeometry(moved, expected, 1e-5f);
  EXPECT_EQ(moved.nodes[1].world, columnMajor(m));
}

// nodeWorldBounds (what Renderer::replaceSceneAfterMove takes) follows the node's vertices through a move, and
// covers only them.
TEST(SceneEdits, NodeWorldBoundsFollowTheMovedVertices) {
  Scene scene = loadScene("builtin:showcase");
  const std::size_t index = *findNode(scene, "glow-sphere");
  const SceneNode node = scene.nodes[index];
  const Bounds3 before = nodeWorldBounds(scene, index);
  ASSERT_FALSE(before.empty());
  EXPECT_LT(glm::length(before.extent()), glm::length(scene.bounds().extent()));
  glm::dmat4 world(1.0);
  world[3] = glm::dvec4(0.5, -0.25, 0.125, 1.0);
  setNodeWorldMatrix(scene, "glow-sphere", world);
  const Bounds3 after = nodeWorldBounds(scene, index);
  EXPECT_NEAR(after.lo.x - before.lo.x, 0.5f, 1e-5f);
  EXPECT_NEAR(after.hi.y - before.hi.y, -0.25f, 1e-5f);
  EXPECT_NEAR(after.hi.z - before.hi.z, 0.125f, 1e-5f);
  for (std::uint32_t v = node.firstVertex; v < node.firstVertex + node.vertexCount; ++v) {
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(scene.positions[v], after.lo)) &&
                glm::all(glm::lessThanEqual(scene.positions[v], after.hi)));
  }
}

// nodeWorldBall holds every vertex of the node, moves with it, and is no larger than the ball around its bounds.
TEST(SceneEdits, NodeWorldBallHoldsTheNodesVerticesAndMovesWithThem) {
  Scene scene = loadScene("builtin:showcase");
  for (const char* name : {"glow-sphere", "red-box", "room"}) {
    SCOPED_TRACE(name);
    const std::size_t index = *findNode(scene, name);
    const SceneNode& node = scene.nodes[index];
    for (int move = 0; move < 2; ++move) {
      const glm::vec4 ball = nodeWorldBall(scene, index);
      const Bounds3 b = nodeWorldBounds(scene, index);
      ASSERT_GE(ball.w, 0.0f);
      EXPECT_LE(ball.w, 0.5001f * glm::length(b.extent()));
      for (std::uint32_t v = node.firstVertex; v < node.firstVertex + node.vertexCount; ++v)
        ASSERT_LE(glm::length(glm::dvec3(scene.positions[v]) - glm::dvec3(glm::vec3(ball))), double(ball.w));
      glm::dmat4 world = scene.nodes[index].world;
      world[3] += glm::dvec4(0.3, -0.1, 0.2, 0.0);
      setNodeWorldMatrix(scene, name, world);
      EXPECT_NEAR(nodeWorldBall(scene, index).x - ball.x, 0.3f, 1e-5f);
    }
  }
  Scene empty = scene;
  empty.nodes[0].vertexCount = 0;
  EXPECT_LT(nodeWorldBall(empty, 0).w, 0.0f);
}

// A mirroring matrix flips the winding back, as the loader does for a mirrored node; moving back restores it.
TEST(SceneEdits, MirroringKeepsFrontFacesAndMovingBackRestores) {
  TempDir dir;
  const std::string file = twoNodeFile(dir, "a.gltf", {{"translation", {3, 0, 0}}});
  const Scene original = loadGltf(file);
  Scene moved = original;
  setNodeWorldMatrix(moved, "right", columnMajor({-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 3, 0, 0, 1}));
  const Scene expected = loadGltf(twoNodeFile(dir, "m.gltf", {{"translation", {3, 0, 0}}, {"scale", {-1, 1, 1}}}));
  expectSameGeometry(moved, expected, 1e-5f);
  EXPECT_GT(test::geometricNormal(moved.positions, moved.triangles[1]).z, 0.0f);
  setNodeWorldMatrix(moved, "right", original.nodes[1].world);
  expectSameGeometry(moved, original, 1e-5f);
}

TEST(SceneEdits, BadEditsAreRefusedAndChangeNothing) {
  TempDir dir;
  Scene s = loadGltf(twoNodeFile(dir, "a.gltf", {{"translation", {3, 0, 0}}}));
  const Scene before = s;
  try {
    setNodeWorldMatrix(s, "middle", glm::dmat4(1.0));
    FAIL() << "unknown node accepted";
  } catch (const SceneError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("'middle'"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("left, right"));
  }
  glm::dmat4 flat(1.0);
  flat[2][2] = 0.0;
  EXPECT_THROW(setNodeWorldMatrix(s, "left", flat), SceneError);
  glm::dmat4 nan(1.0);
  nan[3][0] = std::nan("");
  EXPECT_THROW(setNodeWorldMatrix(s, "left", nan), SceneError);
  EXPECT_EQ(s.positions, before.positions);
  EXPECT_EQ(s.nodes[0].world, before.nodes[0].world);
}

// Issue 14 item 10: a node scaled uniformly by 1e-4 (determinant 1e-12) was refused as "singular"; the test is
// scale-relative now, so tiny and huge uniform scales are moves, and a flattened matrix of any scale is refused.
TEST(SceneEdits, SingularityIsJudgedRelativeToTheScale) {
  TempDir dir;
  Scene s = loadGltf(twoNodeFile(dir, "a.gltf", {{"translation", {3, 0, 0}}}));
  for (const double scale : {1e-4, 1e-6, 1e4}) {
    glm::dmat4 m(scale);
    m[3] = glm::dvec4(3, 0, 0, 1);
    EXPECT_NO_THROW(setNodeWorldMatrix(s, "right", m)) << "uniform scale " << scale;
    EXPECT_EQ(s.nodes[1].world, m);
  }
  glm::dmat4 flatTiny(1e-4);
  flatTiny[3][3] = 1.0;
  flatTiny[2] = glm::dvec4(1e-4, 1e-4, 0, 0);  // third column in the plane of the first two
  EXPECT_THROW(setNodeWorldMatrix(s, "right", flatTiny), SceneError);
}

TEST(SceneEdits, LightEditsAreCheckedThenApplied) {
  Scene s = loadScene("builtin:showcase");
  ASSERT_EQ(s.lights.size(), 2u);
  LightEdit edit;
  edit.position = glm::dvec3(0.0, 2.0, 0.5);
  edit.color = glm::dvec3(1.0, 0.0, 0.0);
  edit.intensity = 3.0;
  editLight(s, 0, edit);
  EXPECT_EQ(s.lights[0].position, glm::vec3(0.0f, 2.0f, 0.5f));
  EXPECT_EQ(s.lights[0].color, glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_EQ(s.lights[0].intensity, 3.0f);
  LightEdit turn;
  turn.direction = glm::dvec3(0.0, -2.0, 0.0);
  editLight(s, 1, turn);
  EXPECT_EQ(s.lights[1].direction, glm::vec3(0.0f, -1.0f, 0.0f));
  const Scene before = s;
  EXPECT_THROW(editLight(s, 2, edit), SceneError);
  LightEdit negative;
  negative.intensity = -1.0;
  EXPECT_THROW(editLight(s, 0, negative), SceneError);
  LightEdit zero;
  zero.direction = glm::dvec3(0.0);
  EXPECT_THROW(editLight(s, 1, zero), SceneError);
  EXPECT_EQ(s.lights[0].intensity, before.lights[0].intensity);
  EXPECT_EQ(s.lights[1].direction, before.lights[1].direction);
}

// Every built-in scene names its objects; together they cover every vertex and triangle exactly once.
TEST(SceneEdits, BuiltinObjectsPartitionTheirScene) {
  for (const std::string& name : builtinSceneNames()) {
    const Scene s = loadScene(name);
    ASSERT_FALSE(s.nodes.empty()) << name;
    std::vector<int> vertexUse(s.positions.size(), 0), triangleUse(s.triangles.size(), 0);
    for (const SceneNode& n : s.nodes) {
      for (std::uint32_t v = n.firstVertex; v < n.firstVertex + n.vertexCount; ++v) ++vertexUse.at(v);
      for (std::uint32_t t = n.firstTriangle; t < n.firstTriangle + n.triangleCount; ++t) {
        ++triangleUse.at(t);
        for (int k = 0; k < 3; ++k) {
          EXPECT_GE(s.triangles[t][k], n.firstVertex) << name << " " << n.name;
          EXPECT_LT(s.triangles[t][k], n.firstVertex + n.vertexCount) << name << " " << n.name;
        }
      }
    }
    EXPECT_EQ(std::count(vertexUse.begin(), vertexUse.end(), 1), static_cast<long>(vertexUse.size())) << name;
    EXPECT_EQ(std::count(triangleUse.begin(), triangleUse.end(), 1), static_cast<long>(triangleUse.size())) << name;
  }
}

}  // namespace
}  // namespace ht
