// mesh_loader_test.cpp - OBJ and OFF parsing, errors, and the glmark2 Stanford bunny.
#include <gtest/gtest.h>

#include <cstdio>
#include <ctime>
#include <filesystem>

#include "common/error.h"
#include "scene/load_scene.h"
#include "scene/mesh_loader.h"
#include "scene_test_util.h"

namespace ht {
namespace {

TEST(SceneObj, VertexReferenceFormsNegativeIndicesAndPolygons) {
  const std::string obj =
      "# comment\n"
      "mtllib x.mtl\n"
      "o thing\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\n"
      "vn 0 0 1\n"
      "usemtl red\n"
      "f 1/1/1 2/2/1 3/3/1\n"  // v/vt/vn
      "f 1//1 3//1 4//1\n"     // v//vn
      "f -4/1 -3/2 -1/3\n"     // v/vt, negative: -1 = vertex 4, -3 = 2, -4 = 1
      "v 2 0 0\n"
      "f 1 2 5 3 4\r\n"  // pentagon, CRLF line end -> fan of 3
      "s off\n";
  SceneLoadReport report;
  const Scene s = parseObj(obj, "inline.obj", &report);
  ASSERT_EQ(s.positions.size(), 5u);
  ASSERT_EQ(s.triangles.size(), 6u);
  EXPECT_EQ(s.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(s.triangles[1], glm::uvec3(0, 2, 3));
  EXPECT_EQ(s.triangles[2], glm::uvec3(0, 1, 3));
  EXPECT_EQ(s.triangles[3], glm::uvec3(0, 1, 4));
  EXPECT_EQ(s.triangles[4], glm::uvec3(0, 4, 2));
  EXPECT_EQ(s.triangles[5], glm::uvec3(0, 2, 3));
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].kind(), MaterialKind::Diffuse);
  EXPECT_TRUE(s.normals.empty());
  EXPECT_EQ(s.triangleMaterial.size(), 6u);
  EXPECT_EQ(report.triangles, 6u);
}

TEST(SceneObj, ScientificNotationAndPlusSigns) {
  const Scene s = parseObj("v 1e-1 +2.5 -3E2\nv 0 0 0\nv 0 1 0\nf 1 2 3\n", "n.obj");
  EXPECT_FLOAT_EQ(s.positions[0].x, 0.1f);
  EXPECT_FLOAT_EQ(s.positions[0].y, 2.5f);
  EXPECT_FLOAT_EQ(s.positions[0].z, -300.0f);
}

std::string objError(const std::string& text) {
  try {
    parseObj(text, "bad.obj");
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), "bad.obj");
    return e.what();
  }
  ADD_FAILURE() << "expected SceneError";
  return {};
}

TEST(SceneObj, BadInputNamesTheLine) {
  EXPECT_NE(objError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n").find("line 4"), std::string::npos);   // out of range
  EXPECT_NE(objError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").find("1-based"), std::string::npos);  // zero index
  EXPECT_NE(objError("v 0 0 0\nf -2 -1 1\n").find("line 2"), std::string::npos);                   // before first
  objError("v 0 0\n");                    // too few coordinates
  objError("v 0 0 0\nv 1 0 0\nf 1 2\n");  // too few face vertices
  objError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
  objError("v 0 0 0\n");  // no faces
}

TEST(SceneOff, PolygonsCommentsAndColourVariant) {
  const std::string off =
      "# CGAL style\n"
      "COFF\n"
      "5 2 0\n"
      "0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 1 1 1 255\n\n0 0 1 1 1 1 255\n"
      "4 0 1 2 3\n"
      "3  0 3 4  255 0 0\n";  // face colour ignored
  const Scene s = parseOff(off, "c.off");
  ASSERT_EQ(s.positions.size(), 5u);
  ASSERT_EQ(s.triangles.size(), 3u);
  EXPECT_EQ(s.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(s.triangles[1], glm::uvec3(0, 2, 3));
  EXPECT_EQ(s.triangles[2], glm::uvec3(0, 3, 4));
  EXPECT_FLOAT_EQ(s.positions[4].z, 1.0f);
}

TEST(SceneOff, CountsOnTheHeaderLine) {
  const Scene s = parseOff("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "h.off");
  EXPECT_EQ(s.triangles.size(), 1u);
}

TEST(SceneOff, BadInputIsRefused) {
  const auto offError = [](const std::string& text) { EXPECT_THROW(parseOff(text, "bad.off"), SceneError) << text; };
  offError("PLY\n3 1 0\n");
  offError("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");  // index out of range
  offError("OFF\n3 1 0\n0 0 0\n1 0 0\n");                  // truncated
  offError("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n");    // face shorter than its count
  offError("OFF\n99999999 1 0\n0 0 0\n");                  // counts the file cannot hold
  offError("4OFF\n3 1 0\n");
}

TEST(SceneMeshFiles, LoadSceneDispatchesOnCaseInsensitiveExtension) {
  test::TempDir dir;
  const std::string obj = dir.write("TRI.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string off = dir.write("tri.Off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(loadScene(obj).triangles.size(), 1u);
  EXPECT_EQ(loadScene(off).triangles.size(), 1u);
  EXPECT_EQ(loadScene(obj).name, obj);
  try {
    loadScene(dir.file("missing.obj"));
    ADD_FAILURE() << "expected SceneError";
  } catch (const SceneError& e) { EXPECT_EQ(e.file(), dir.file("missing.obj")); }
}

TEST(SceneMeshFiles, Glmark2BunnyLoadsQuickly) {
  const std::string bunny = "/usr/share/glmark2/models/bunny.obj";
  if (!std::filesystem::exists(bunny)) GTEST_SKIP() << bunny << " not installed (apt-get install glmark2-data)";
  // Process CPU time, not wall time: the test machine may be shared with parallel builds.
  const std::clock_t c0 = std::clock();
  const Scene s = loadScene(bunny);
  const double ms = 1000.0 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  EXPECT_EQ(s.triangles.size(), 69666u);  // docs/TOOLCHAIN.md §7: 34,835 v / 69,666 tris
  EXPECT_EQ(s.positions.size(), 34835u);
  EXPECT_FALSE(s.bounds().empty());
  std::printf("bunny: %zu triangles in %.1f ms CPU\n", s.triangles.size(), ms);
#if defined(NDEBUG) && !defined(HT_SANITIZED_BUILD)  // optimised, uninstrumented builds only
  EXPECT_LT(ms, 100.0);
#endif
}

}  // namespace
}  // namespace ht
