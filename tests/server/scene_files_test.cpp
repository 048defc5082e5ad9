// scene_files_test.cpp - issue 14 item 11: LoadScene opens the scene file once beneath the scene root and loads
// those bytes (a symlink swapped in after the check cannot lead out), and the content key covers a .gltf's external
// buffers (two scenes that differ only there never share a BVH).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <fstream>
#include <thread>

#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

using grpc::StatusCode;

class SceneFilesTest : public InProcessDaemonTest<SceneFilesTest> {};

std::string oneTriangleObj() { return "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"; }

// A .gltf with one triangle whose positions live in the external `tri.bin`.
std::string externalBufferGltf() {
  return R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "tri.bin", "byteLength": 36}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [9, 9, 0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}],
    "scenes": [{"nodes": [0]}], "scene": 0})";
}

std::string triangleBin(float size) {
  const float xyz[9] = {0, 0, 0, size, 0, 0, 0, size, 0};
  std::string bytes(sizeof xyz, '\0');
  std::memcpy(bytes.data(), xyz, sizeof xyz);
  return bytes;
}

// The swapper flips `swap.obj` between a fresh in-root cube (new bytes each time, so every load builds) and a
// symlink to a one-triangle file outside the root. Before the fix the daemon checked the path, then read and
// loaded it by path again: the outside file was loaded. Now each load is the cube or PERMISSION_DENIED.
TEST_F(SceneFilesTest, ASymlinkSwappedInDuringALoadNeverLeadsOut) {
  const auto root = files_->sceneRoot();
  const auto outside = files_->dir.path / "outside_one_triangle.obj";
  writeText(outside, oneTriangleObj());
  writeText(root / "swap.obj", cubeObj());  // there from the first load on; rename() replaces it atomically
  std::atomic<bool> stop{false};
  std::thread swapper([&] {
    for (int i = 0; !stop; ++i) {
      std::error_code ec;  // no exceptions on this thread: a throw here would terminate the test program
      std::ofstream(root / "swap_tmp.obj") << cubeObj() << "# " << i << "\n";
      std::filesystem::rename(root / "swap_tmp.obj", root / "swap.obj", ec);
      std::filesystem::remove(root / "swap_lnk", ec);
      std::filesystem::create_symlink(outside, root / "swap_lnk", ec);
      std::filesystem::rename(root / "swap_lnk", root / "swap.obj", ec);
    }
  });
  int loaded = 0, denied = 0;
  for (int i = 0; i < 300; ++i) {
    v1::SceneHandle handle;
    const grpc::Status status = loadScene(*stub_, "swap.obj", &handle);
    if (status.ok()) {
      ++loaded;
      EXPECT_EQ(handle.triangles(), 12u) << "load " << i << " read the file outside the scene root";
    } else {
      ++denied;
      EXPECT_EQ(status.error_code(), StatusCode::PERMISSION_DENIED) << status.error_message();
    }
  }
  stop = true;
  swapper.join();
  EXPECT_GT(loaded, 0);
  RecordProperty("loaded", loaded);
  RecordProperty("denied", denied);
}

// Before the fix the key hashed only the .gltf text: a changed tri.bin was "reused" with the old BVH.
TEST_F(SceneFilesTest, TheContentKeyCoversExternalBuffers) {
  const auto dir = files_->sceneRoot() / "ext";
  std::filesystem::create_directories(dir);
  writeText(dir / "tri.gltf", externalBufferGltf());
  writeText(dir / "tri.bin", triangleBin(1.0f));
  v1::SceneHandle first, second, again;
  ASSERT_TRUE(loadScene(*stub_, "ext/tri.gltf", &first).ok());
  writeText(dir / "tri.bin", triangleBin(9.0f));
  ASSERT_TRUE(loadScene(*stub_, "ext/tri.gltf", &second).ok());
  EXPECT_FALSE(second.reused()) << "a different external buffer shared the first scene's BVH";
  ASSERT_TRUE(loadScene(*stub_, "ext/tri.gltf", &again).ok());
  EXPECT_TRUE(again.reused());  // the same bytes everywhere still share
}

// The shape from issue 14 item 3: a ~150 KB GLB whose 4,045 nodes instance one 12,288-triangle mesh (49.7 M
// triangles). It was refused by limits.max_triangles only after a full load (6.9 GB, 20 s); now from the accessor
// counts before anything is allocated, and the daemon's memory does not move.
std::string instancedGlb() {
  const int triangles = 12288, nodes = 4045;
  std::string bin;
  const float xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  bin.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  for (int t = 0; t < triangles; ++t) {
    const std::uint16_t tri[3] = {0, 1, static_cast<std::uint16_t>(2 + t % 2)};
    bin.append(reinterpret_cast<const char*>(tri), sizeof tri);
  }
  std::string nodeList, rootList;
  for (int n = 0; n < nodes; ++n) {
    nodeList += std::string(n ? "," : "") + R"({"mesh":0})";
    rootList += std::string(n ? "," : "") + std::to_string(n);
  }
  std::string json = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":)" + std::to_string(bin.size()) +
                     R"(}],"bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":)" +
                     std::to_string(bin.size() - 48) +
                     R"(}],"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],)"
                     R"("max":[1,1,0]},{"bufferView":1,"componentType":5123,"count":)" +
                     std::to_string(3 * triangles) +
                     R"(,"type":"SCALAR"}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
                     R"("nodes":[)" +
                     nodeList + R"(],"scenes":[{"nodes":[)" + rootList + R"(]}],"scene":0})";
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin += '\0';
  const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  return "glTF" + u32(2) + u32(static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size())) +
         u32(static_cast<std::uint32_t>(json.size())) + "JSON" + json + u32(static_cast<std::uint32_t>(bin.size())) +
         std::string("BIN\0", 4) + bin;
}

TEST_F(SceneFilesTest, AnInstancedGlbIsRefusedBeforeLoading) {
  writeText(files_->sceneRoot() / "instanced.glb", instancedGlb());
  v1::StatusResponse before, after;
  grpc::ClientContext c1, c2;
  ASSERT_TRUE(stub_->Status(&c1, v1::StatusRequest(), &before).ok());
  const auto start = std::chrono::steady_clock::now();
  v1::SceneHandle handle;
  const grpc::Status status = loadScene(*stub_, "instanced.glb", &handle);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(status.error_code(), StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
  EXPECT_NE(status.error_message().find("triangles or more after instancing"), std::string::npos)
      << status.error_message();
  EXPECT_LT(seconds, 3.0);
  ASSERT_TRUE(stub_->Status(&c2, v1::StatusRequest(), &after).ok());
  EXPECT_LT(after.resident_kib(), before.resident_kib() + 100'000);
}

// Item 10: upload errors printed the daemon's absolute work path, and a full work directory was reported as "output
// disk full". Uploads load from memory now: errors name the client's file, and the work directory is not written
// (here it is gone altogether).
TEST_F(SceneFilesTest, UploadsNeitherWriteNorNameTheWorkDirectory) {
  std::filesystem::remove_all(files_->config().workDir);
  v1::SceneHandle handle;
  const grpc::Status broken = uploadScene(*stub_, "broken.obj", "v 0 0 0\nf 1 2 7\n", &handle);
  EXPECT_EQ(broken.error_code(), StatusCode::INVALID_ARGUMENT) << broken.error_message();
  EXPECT_EQ(broken.error_message().rfind("broken.obj: ", 0), 0u) << broken.error_message();
  EXPECT_EQ(broken.error_message().find(files_->dir.path.string()), std::string::npos) << broken.error_message();
  const grpc::Status good = uploadScene(*stub_, "cube.obj", cubeObj(), &handle);
  EXPECT_TRUE(good.ok()) << good.error_message();
  EXPECT_EQ(handle.triangles(), 12u);
}

// External files stay beneath the scene file's folder: a buffer URI leading out is refused.
TEST_F(SceneFilesTest, AnExternalUriLeadingOutIsRefused) {
  const auto dir = files_->sceneRoot() / "esc";
  std::filesystem::create_directories(dir);
  std::string gltf = externalBufferGltf();
  gltf.replace(gltf.find("tri.bin"), 7, "../../secret.bin");
  writeText(dir / "esc.gltf", gltf);
  writeText(files_->dir.path / "secret.bin", triangleBin(1.0f));
  v1::SceneHandle handle;
  const grpc::Status status = loadScene(*stub_, "esc/esc.gltf", &handle);
  EXPECT_EQ(status.error_code(), StatusCode::INVALID_ARGUMENT) << status.error_message();
  EXPECT_NE(status.error_message().find("outside"), std::string::npos) << status.error_message();
}

}  // namespace
}  // namespace ht::server::test
