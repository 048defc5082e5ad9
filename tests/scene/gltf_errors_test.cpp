// gltf_errors_test.cpp - broken and hostile glTF files: each must throw a SceneError whose file() is the
// path and whose message says what is wrong.
#include <gtest/gtest.h>

#include "common/error.h"
#include "scene/gltf_loader.h"
#include "scene/load_scene.h"
#include "scene_test_util.h"

namespace ht {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using test::TempDir;

// Loads `path`, expects a SceneError naming it, returns the message for further checks.
std::string expectSceneError(const std::string& path) {
  try {
    loadScene(path);
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), path);
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected SceneError, got: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected SceneError for " << path << ", but it loaded";
  return {};
}

// A valid one-triangle document (indexed with u16) the tests below break in one place.
GltfBuilder validTriangle() {
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int idx = b.addData(std::vector<std::uint16_t>{0, 1, 2, 0}, test::kUShort, "SCALAR", 1);
  b.doc["accessors"][idx]["count"] = 3;
  b.setScene({b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
  return b;
}

TEST(SceneGltfErrors, ValidBaselineLoads) {
  TempDir dir;
  EXPECT_EQ(loadScene(validTriangle().writeGltf(dir, "ok.gltf")).triangles.size(), 1u);
}

TEST(SceneGltfErrors, MissingFile) {
  TempDir dir;
  EXPECT_NE(expectSceneError(dir.file("nope.gltf")).find("not found"), std::string::npos);
}

TEST(SceneGltfErrors, NotJson) {
  TempDir dir;
  EXPECT_NE(expectSceneError(dir.write("bad.gltf", "this is { not json")).find("JSON"), std::string::npos);
}

TEST(SceneGltfErrors, Gltf1FileIsRefused) {
  TempDir dir;
  const std::string msg = expectSceneError(dir.write("old.gltf", R"({"asset": {"version": "1.0"}, "meshes": {}})"));
  EXPECT_NE(msg.find("1.0"), std::string::npos);
}

TEST(SceneGltfErrors, TruncatedGlb) {
  TempDir dir;
  const std::string glb = validTriangle().glbBytes();
  EXPECT_NE(expectSceneError(dir.write("cut.glb", glb.substr(0, glb.size() / 2))).find("truncated"), std::string::npos);
  expectSceneError(dir.write("tiny.glb", glb.substr(0, 10)));
}

TEST(SceneGltfErrors, GlbBinChunkShorterThanDeclared) {
  TempDir dir;
  std::string glb = validTriangle().glbBytes();
  const std::size_t jsonLen = static_cast<std::uint8_t>(glb[12]) | static_cast<std::uint8_t>(glb[13]) << 8;
  glb[20 + jsonLen] = static_cast<char>(0xF0);  // BIN chunk length low byte: now larger than what follows
  expectSceneError(dir.write("binlen.glb", glb));
}

TEST(SceneGltfErrors, BufferTooShortForItsAccessor) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["accessors"][0]["count"] = 10;  // 10 VEC3 floats = 120 bytes, the bufferView holds 36
  EXPECT_NE(expectSceneError(b.writeGltf(dir, "short.gltf")).find("too short"), std::string::npos);
}

TEST(SceneGltfErrors, BufferViewBeyondItsBuffer) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["bufferViews"][0]["byteOffset"] = 1000;
  expectSceneError(b.writeGltf(dir, "view.gltf"));
}

TEST(SceneGltfErrors, IndexOutOfRange) {
  TempDir dir;
  GltfBuilder b;
  const int pos = b.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int idx = b.addData(std::vector<std::uint16_t>{0, 1, 7, 0}, test::kUShort, "SCALAR", 1);
  b.doc["accessors"][idx]["count"] = 3;
  b.setScene({b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
  EXPECT_NE(expectSceneError(b.writeGltf(dir, "idx.gltf")).find("out of range"), std::string::npos);
}

TEST(SceneGltfErrors, AccessorReferencesMissingBufferView) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["accessors"][0]["bufferView"] = 9;
  EXPECT_NE(expectSceneError(b.writeGltf(dir, "noview.gltf")).find("bufferView 9"), std::string::npos);
}

TEST(SceneGltfErrors, RequiredDracoIsRefusedWithHowToDecompress) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  const std::string msg = expectSceneError(b.writeGlb(dir, "draco.glb"));
  EXPECT_NE(msg.find("Draco"), std::string::npos);
  EXPECT_NE(msg.find("decompress"), std::string::npos);
}

TEST(SceneGltfErrors, UnknownRequiredExtension) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["extensionsRequired"] = {"KHR_lights_punctual", "VENDOR_made_up"};
  EXPECT_NE(expectSceneError(b.writeGltf(dir, "ext.gltf")).find("VENDOR_made_up"), std::string::npos);
}

TEST(SceneGltfErrors, OptionalUnknownExtensionOnlyWarns) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["extensionsUsed"] = {"VENDOR_made_up"};
  SceneLoadReport report;
  EXPECT_EQ(loadScene(b.writeGltf(dir, "opt.gltf"), report).triangles.size(), 1u);
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_NE(report.warnings[0].find("VENDOR_made_up"), std::string::npos);
}

TEST(SceneGltfErrors, NodeCycleIsRefused) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["nodes"][0]["children"] = {1};
  b.doc["nodes"].push_back({{"children", {0}}});
  EXPECT_NE(expectSceneError(b.writeGltf(dir, "cycle.gltf")).find("twice"), std::string::npos);
}

TEST(SceneGltfErrors, MissingMeshAndMaterialReferences) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["nodes"][0]["mesh"] = 4;
  expectSceneError(b.writeGltf(dir, "mesh.gltf"));
  GltfBuilder c = validTriangle();
  c.doc["meshes"][0]["primitives"][0]["material"] = 3;
  expectSceneError(c.writeGltf(dir, "material.gltf"));
}

// The triangle budget is checked from accessor counts, before any allocation: a count of 600 M indices
// in a 8-byte buffer is refused as "too many triangles", not attempted.
TEST(SceneGltfErrors, AbsurdTriangleCountRefusedBeforeAllocating) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["accessors"][1]["count"] = 600000000;
  EXPECT_NE(expectSceneError(b.writeGltf(dir, "huge.gltf")).find("triangles"), std::string::npos);
}

TEST(SceneGltfErrors, OversizedImageRefusedBeforeDecoding) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  std::string png = test::encodePng(1, 1, 4, {1, 2, 3, 4});
  png[16] = 0;
  png[17] = 0;
  png[18] = 0x4E;
  png[19] = 0x20;  // IHDR width = 20000 (CRC now wrong: never decoded)
  b.doc["images"] = json::array({{{"bufferView", b.addBufferView(png)}, {"mimeType", "image/png"}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  EXPECT_NE(expectSceneError(b.writeGltf(dir, "bigimage.gltf")).find("20000"), std::string::npos);
}

TEST(SceneGltfErrors, NonPngJpegImageRefused) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["images"] = json::array({{{"uri", "data:image/gif;base64," + test::base64("GIF89a....")}}});
  expectSceneError(b.writeGltf(dir, "gif.gltf"));
}

TEST(SceneGltfErrors, ExternalUriOutsideTheSceneFolderIsNotRead) {
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "scene");
  GltfBuilder b = validTriangle();
  dir.write("secret.bin", b.bin);  // would make the file load if the loader followed ".."
  nlohmann::json d = b.doc;
  d["buffers"] = json::array({{{"byteLength", b.bin.size()}, {"uri", "../secret.bin"}}});
  const std::string path = dir.write("scene/escape.gltf", d.dump());
  expectSceneError(path);
}

TEST(SceneGltfErrors, MissingExternalTextureFile) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  b.doc["images"] = json::array({{{"uri", "missing.png"}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  EXPECT_NE(expectSceneError(b.writeGltf(dir, "notex.gltf")).find("missing.png"), std::string::npos);
}

TEST(SceneGltfErrors, AbsurdJsonNestingIsRefused) {
  TempDir dir;
  GltfBuilder b = validTriangle();
  const std::size_t depth = 100000;
  std::string doc = b.doc.dump();
  doc.pop_back();  // reopen the top-level object and add a deeply nested `extras`
  doc += ",\"extras\":" + std::string(depth, '[') + std::string(depth, ']') + "}";
  EXPECT_NE(expectSceneError(dir.write("deep.gltf", doc)).find("nesting"), std::string::npos);
}

TEST(SceneGltfErrors, GlbExtensionWithoutMagic) {
  TempDir dir;
  EXPECT_NE(expectSceneError(dir.write("json.glb", R"({"asset":{"version":"2.0"}})")).find("magic"), std::string::npos);
}

TEST(SceneGltfErrors, FileWithoutTriangles) {
  TempDir dir;
  expectSceneError(dir.write("empty.gltf", R"({"asset":{"version":"2.0"}})"));
}

}  // namespace
}  // namespace ht
