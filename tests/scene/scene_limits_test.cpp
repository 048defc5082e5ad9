// scene_limits_test.cpp - issue 14 item 3: every count limit (triangles, vertices, nodes, instances, texture pixels)
// is computed from the file's headers and refused before the memory is allocated. The shape from the issue: a small
// GLB that instances one mesh to 49.7 M triangles, refused in milliseconds without growing the process.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <chrono>

#include "common/error.h"
#include "scene/load_scene.h"
#include "scene/scene_limits.h"
#include "scene_test_util.h"

namespace ht {
namespace {

using ::testing::HasSubstr;

long peakRssKiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

// 12,288 indexed triangles over 4 vertices, instanced by 4,045 nodes: 49,704,960 triangles from a ~150 KB GLB.
std::string instancedGlb() {
  test::GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
  std::vector<std::uint16_t> indices;
  for (int t = 0; t < 12288; ++t) indices.insert(indices.end(), {0, 1, static_cast<std::uint16_t>(2 + t % 2)});
  const int idx = b.addData(indices, test::kUShort, "SCALAR", 1);
  const int mesh = b.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  std::vector<int> roots;
  for (int n = 0; n < 4045; ++n) roots.push_back(b.addNode({{"mesh", mesh}}));
  b.setScene(roots);
  return b.glbBytes();
}

SceneLimitExceeded expectOverLimit(const SceneSource& source, const SceneLimits& limits) {
  try {
    loadScene(source, limits);
  } catch (const SceneLimitExceeded& e) { return e; }
  ADD_FAILURE() << "no SceneLimitExceeded for " << source.name;
  return SceneLimitExceeded("", "");
}

TEST(SceneLimits, AnInstancedGlbIsRefusedFromItsHeadersBeforeLoading) {
  const SceneSource source{"instanced.glb", instancedGlb(), {}, {}};
  ASSERT_LT(source.bytes.size(), 200'000u);
  SceneLimits limits;
  limits.maxTriangles = 5'000'000;  // holotraced's default limits.max_triangles
  limits.maxVertices = 3 * limits.maxTriangles;
  const long rssBefore = peakRssKiB();
  const auto start = std::chrono::steady_clock::now();
  const SceneLimitExceeded e = expectOverLimit(source, limits);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_THAT(e.what(), HasSubstr("triangles or more after instancing"));
  EXPECT_THAT(e.what(), HasSubstr("limit of 5000000"));
  EXPECT_LT(seconds, 2.0);                       // was a full 20 s load
  EXPECT_LT(peakRssKiB() - rssBefore, 100'000);  // was 6.9 GB before the refusal
}

TEST(SceneLimits, InstancesNodesAndTexturePixelsHaveLimits) {
  const SceneSource source{"instanced.glb", instancedGlb(), {}, {}};
  SceneLimits fewInstances;
  fewInstances.maxInstances = 100;
  EXPECT_THAT(expectOverLimit(source, fewInstances).what(), HasSubstr("mesh instances"));
  SceneLimits fewNodes;
  fewNodes.maxNodes = 1000;
  EXPECT_THAT(expectOverLimit(source, fewNodes).what(), HasSubstr("4045 nodes"));

  test::GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  b.setScene({b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", pos}}}})}})});
  const std::string png = test::encodePng(64, 64, 3, std::vector<std::uint8_t>(64 * 64 * 3, 200));
  b.doc["images"] = nlohmann::json::array();
  for (int i = 0; i < 3; ++i)
    b.doc["images"].push_back({{"bufferView", b.addBufferView(png)}, {"mimeType", "image/png"}});
  SceneLimits fewPixels;
  fewPixels.maxTexturePixels = 2 * 64 * 64;  // two of the three textures
  const SceneSource textured{"textured.glb", b.glbBytes(), {}, {}};
  EXPECT_THAT(expectOverLimit(textured, fewPixels).what(), HasSubstr("12288 texture pixels"));
  EXPECT_NO_THROW(loadScene(textured));
}

TEST(SceneLimits, OffHeaderCountsAndObjLinesAreChecked) {
  SceneLimits small;
  small.maxVertices = 1000;
  small.maxTriangles = 10;
  const SceneSource off{"big.off", "OFF\n2000 1 0\n" + std::string(2000 * 6, ' '), {}, {}};
  EXPECT_THAT(expectOverLimit(off, small).what(), HasSubstr("2000 vertices (OFF header)"));
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (int i = 0; i < 11; ++i) obj += "f 1 2 3\n";
  EXPECT_THAT(expectOverLimit({"many.obj", obj, {}, {}}, small).what(), HasSubstr("11 triangles or more at line 14"));
}

}  // namespace
}  // namespace ht
