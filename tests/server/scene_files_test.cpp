// scene_files_test.cpp - issue 14 item 11: LoadScene opens the scene file once beneath the scene root and loads
// those bytes (a symlink swapped in after the check cannot lead out), and the content key covers a .gltf's external
// buffers (two scenes that differ only there never share a BVH).
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
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
  std::atomic<bool> stop{false};
  std::thread swapper([&] {
    for (int i = 0; !stop; ++i) {
      writeText(root / "swap_tmp.obj", cubeObj() + "# " + std::to_string(i) + "\n");
      std::filesystem::rename(root / "swap_tmp.obj", root / "swap.obj");
      std::error_code ec;
      std::filesystem::remove(root / "swap_lnk", ec);
      std::filesystem::create_symlink(outside, root / "swap_lnk");
      std::filesystem::rename(root / "swap_lnk", root / "swap.obj");
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
