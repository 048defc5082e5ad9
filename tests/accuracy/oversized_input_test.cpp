// Oversized inputs are refused before allocation (issue 4, docs/ACCURACY.md "Hostile input"): scenes that claim
// about 10^9 triangles through a glTF accessor count or an OFF header, files past limits::kMaxFileBytes, and display
// panels of 100k x 100k pixels. Each case must throw the project's error type naming the file and the field/count,
// and (scenes) the largest single heap allocation made while refusing must stay small: a loader that reserved
// memory for the claimed count first would allocate gigabytes (or die) before failing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <string>

#include "camera_models/display_config.h"
#include "camera_models/looking_glass_calibration.h"
#include "common/error.h"
#include "scene/load_scene.h"
#include "scene/mesh_loader.h"
#include "scene/scene_limits.h"

// Largest single operator-new request while a LargestAllocation probe is alive (replacement of the global
// allocation functions, [new.delete.single]; they forward to malloc/free).
namespace {
std::atomic<bool> gWatching{false};
std::atomic<std::size_t> gLargest{0};

void* allocate(std::size_t size) {
  if (gWatching.load(std::memory_order_relaxed)) {
    std::size_t seen = gLargest.load(std::memory_order_relaxed);
    while (size > seen && !gLargest.compare_exchange_weak(seen, size)) {}
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace ht {
namespace {

constexpr std::size_t kSmallAllocation = std::size_t{16} << 20;  // 16 MiB: far below any claimed size here

class LargestAllocation {
 public:
  LargestAllocation() {
    gLargest = 0;
    gWatching = true;
  }
  ~LargestAllocation() { gWatching = false; }
  std::size_t bytes() const { return gLargest.load(); }
};

std::filesystem::path scratchDir() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("holotrace-oversized-" + std::to_string(::getpid()) + "-" +
                                                ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::create_directories(dir);
  return dir;
}

// Removes the test's scratch folder afterwards.
class OversizedInput : public ::testing::Test {
 protected:
  void TearDown() override { std::filesystem::remove_all(scratchDir()); }
};

std::filesystem::path writeFile(const std::string& name, const std::string& text) {
  const auto path = scratchDir() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// SceneError from loading `path`; fails the test if the load succeeds or throws anything else.
std::string sceneErrorOf(const std::string& path, std::size_t& largestAllocation) {
  LargestAllocation probe;
  try {
    (void)loadScene(path);
  } catch (const SceneError& e) {
    largestAllocation = probe.bytes();
    EXPECT_GT(largestAllocation, 0u) << "the allocation probe saw no allocation at all";
    EXPECT_EQ(e.file(), path);
    std::printf("refused: %s (largest allocation %zu bytes)\n", e.what() + path.size() + 2, largestAllocation);
    return e.what();
  }
  ADD_FAILURE() << path << " loaded, expected a SceneError";
  return {};
}

// One triangle (36 bytes of positions, indices 0 1 2 as u16) in a data-URI buffer; `accessors` and `attributes`
// are spliced in so each test can claim its own counts.
std::string gltfWithClaims(const std::string& attributes, const std::string& indices, const std::string& accessors) {
  // base64 of 9 floats (0 0 0, 1 0 0, 0 1 0) followed by u16 0 1 2 and two padding bytes (42 bytes + 2).
  const std::string data = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=";
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{)" +
         attributes + "}" + indices +
         R"(}]}],)"
         R"("buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,)" +
         data +
         R"("}],)"
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],)"
         R"("accessors":[)" +
         accessors + "]}";
}

const std::string kPositionsOk = R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"})";

TEST_F(OversizedInput, OffHeaderClaimingABillionFacesIsRefusedBeforeReserving) {
  std::size_t largest = 0;
  const auto path = writeFile("billion.off", "OFF\n1000000000 1000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string what = sceneErrorOf(path.string(), largest);
  EXPECT_NE(what.find("1000000000 vertices and 1000000000 faces"), std::string::npos) << what;
  EXPECT_LT(largest, kSmallAllocation);
}

TEST_F(OversizedInput, OffFaceClaimingABillionCornersIsRefused) {
  std::size_t largest = 0;
  const auto path = writeFile("corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000 0 1 2\n");
  const std::string what = sceneErrorOf(path.string(), largest);
  EXPECT_NE(what.find("line 6"), std::string::npos) << what;
  EXPECT_LT(largest, kSmallAllocation);
}

TEST_F(OversizedInput, ObjFaceIndexFarBeyondTheVerticesIsRefused) {
  for (const std::string face : {"f 1 2 1000000000", "f 1 2 -1000000000", "f 1 2 99999999999999999999999"}) {
    std::size_t largest = 0;
    const auto path = writeFile("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n" + face + "\n");
    const std::string what = sceneErrorOf(path.string(), largest);
    EXPECT_NE(what.find("line 4"), std::string::npos) << face << ": " << what;
    EXPECT_LT(largest, kSmallAllocation) << face;
  }
}

TEST_F(OversizedInput, GltfPositionCountOfThreeBillionIsRefusedBeforeReadingGeometry) {
  // Non-indexed TRIANGLES: 3e9 positions claim 1e9 triangles; the bufferView holds 36 bytes.
  std::size_t largest = 0;
  const auto path = writeFile(
      "billion.gltf", gltfWithClaims(R"("POSITION":0)", "",
                                     R"({"bufferView":0,"componentType":5126,"count":3000000000,"type":"VEC3"})"));
  const std::string what = sceneErrorOf(path.string(), largest);
  EXPECT_NE(what.find("more than the limit of " + std::to_string(limits::kMaxTriangles)), std::string::npos) << what;
  EXPECT_LT(largest, kSmallAllocation);
}

TEST_F(OversizedInput, GltfIndexCountOfThreeBillionIsRefusedBeforeReadingGeometry) {
  std::size_t largest = 0;
  const auto path = writeFile(
      "indices.gltf",
      gltfWithClaims(R"("POSITION":0)", R"(,"indices":1)",
                     kPositionsOk + R"(,{"bufferView":1,"componentType":5123,"count":3000000000,"type":"SCALAR"})"));
  const std::string what = sceneErrorOf(path.string(), largest);
  EXPECT_NE(what.find("more than the limit of " + std::to_string(limits::kMaxTriangles)), std::string::npos) << what;
  EXPECT_LT(largest, kSmallAllocation);
}

TEST_F(OversizedInput, GltfAttributeCountOfABillionIsRefusedWithOrWithoutABufferView) {
  // NORMAL is not part of the triangle budget, so its own count must be checked against the stored bytes (with a
  // bufferView) or the zero-fill cap (without one, glTF 2.0 "Sparse Accessors").
  for (const std::string normal : {R"({"bufferView":0,"componentType":5126,"count":1000000000,"type":"VEC3"})",
                                   R"({"componentType":5126,"count":1000000000,"type":"VEC3"})"}) {
    std::size_t largest = 0;
    const auto path =
        writeFile("normals.gltf", gltfWithClaims(R"("POSITION":0,"NORMAL":1)", "", kPositionsOk + "," + normal));
    const std::string what = sceneErrorOf(path.string(), largest);
    EXPECT_NE(what.find("accessor 1"), std::string::npos) << what;
    EXPECT_LT(largest, kSmallAllocation) << normal;
  }
}

TEST_F(OversizedInput, GlbHeaderClaimingFourGigabytesIsRefused) {
  std::string glb = "glTF";
  const std::uint32_t header[2] = {2u, 0xFFFFFFF0u};  // version 2, total length ~4 GiB
  glb.append(reinterpret_cast<const char*>(header), sizeof header);
  const std::uint32_t chunk[2] = {0xFFFFFF00u, 0x4E4F534Au};  // JSON chunk claiming ~4 GiB
  glb.append(reinterpret_cast<const char*>(chunk), sizeof chunk);
  glb += "{}  ";
  std::size_t largest = 0;
  const auto path = writeFile("huge.glb", glb);
  const std::string what = sceneErrorOf(path.string(), largest);
  EXPECT_NE(what.find("4294967280"), std::string::npos) << what;
  EXPECT_LT(largest, kSmallAllocation);
}

TEST_F(OversizedInput, SceneFileLargerThanTheCapIsRefusedWithoutReadingIt) {
  // A sparse file (no disk blocks) just past limits::kMaxFileBytes.
  const auto path = scratchDir() / "huge.obj";
  { std::ofstream(path, std::ios::binary) << "v 0 0 0\n"; }
  std::filesystem::resize_file(path, limits::kMaxFileBytes + 1);
  std::size_t largest = 0;
  const std::string what = sceneErrorOf(path.string(), largest);
  EXPECT_NE(what.find(std::to_string(limits::kMaxFileBytes)), std::string::npos) << what;
  EXPECT_LT(largest, kSmallAllocation);
  std::filesystem::remove(path);
}

// ConfigError for `json`, with the field it names.
std::string configErrorField(const std::string& json) {
  try {
    (void)parseDisplayConfig(json, "oversized.json", {});
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "oversized.json");
    EXPECT_NE(std::string(e.what()).find("100000"), std::string::npos) << e.what();
    return e.field();
  }
  ADD_FAILURE() << "accepted: " << json;
  return {};
}

TEST_F(OversizedInput, PanelOfOneHundredThousandPixelsSquareIsRefused) {
  // Raw visual.json (LookingGlassCalibration screenW/screenH, at most 32768).
  EXPECT_EQ(configErrorField(R"({"pitch":47.6,"slope":-5.5,"center":0.1,"viewCone":40,"invView":1,"DPI":324,)"
                             R"("screenW":100000,"screenH":100000,"flipImageX":0,"flipImageY":0,"flipSubp":0})"),
            "screenW");
  // Our format: pinhole image, integral panel.
  EXPECT_EQ(configErrorField(R"({"model":"pinhole","pinhole":{"width":100000,"height":100000}})"), "pinhole.width");
  EXPECT_EQ(configErrorField(R"({"model":"integral","integral":{"panelWidth":100000,"panelHeight":100000,)"
                             R"("pixelPitch":0.1,"lensPitch":0.77,"gap":2.0,"focalLength":2.5,"viewerDistance":500}})"),
            "integral.panelWidth");
}

}  // namespace
}  // namespace ht
