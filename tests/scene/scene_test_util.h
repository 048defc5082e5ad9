// scene_test_util.h - helpers for the scene tests: a temporary folder, base64, a tiny PNG encoder, and a
// builder that assembles glTF 2.0 documents (JSON + one binary buffer) written as .gltf (data URI or
// external .bin) or .glb.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace ht::test {

// A fresh folder under the system temp dir, removed with its contents on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::filesystem::path path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const;

 private:
  std::filesystem::path path_;
};

std::string base64(const std::string& bytes);

// PNG (8-bit, colour type 2 = RGB or 6 = RGBA, stored/uncompressed deflate) of `pixels` rows top to bottom.
std::string encodePng(std::uint32_t width, std::uint32_t height, int channels, const std::vector<std::uint8_t>& pixels);

// glTF component types and modes (spec constants), for readable tests.
enum : int { kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125, kFloat = 5126 };
enum : int { kPoints = 0, kLines = 1, kTriangles = 4, kStrip = 5, kFan = 6 };

class GltfBuilder {
 public:
  GltfBuilder();
  nlohmann::json doc;  // asset, and whatever the test adds; buffers are added when writing
  std::string bin;     // contents of buffer 0

  // Appends raw bytes (4-byte aligned) as a bufferView and returns its index.
  int addBufferView(const std::string& bytes, std::size_t byteStride = 0);
  int addAccessor(int bufferView, int componentType, std::size_t count, const std::string& type,
                  bool normalized = false, std::size_t byteOffset = 0);
  template <class T>
  int addData(const std::vector<T>& values, int componentType, const std::string& type, std::size_t components,
              bool normalized = false) {
    const std::string bytes(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    const std::size_t componentBytes = componentType == kFloat || componentType == kUInt     ? 4
                                       : componentType == kShort || componentType == kUShort ? 2
                                                                                             : 1;
    return addAccessor(addBufferView(bytes), componentType, bytes.size() / (componentBytes * components), type,
                       normalized);
  }
  int addPositions(const std::vector<glm::vec3>& p);
  int addNormals(const std::vector<glm::vec3>& n);
  // One mesh with one primitive {attributes, indices (optional), mode, material (optional)}; returns mesh index.
  int addMesh(const nlohmann::json& primitive);
  int addNode(const nlohmann::json& node);           // returns node index
  void setScene(const std::vector<int>& rootNodes);  // one scene, the default

  std::string writeGltf(const TempDir& dir, const std::string& name) const;  // data-URI buffer
  std::string writeGltfExternal(const TempDir& dir, const std::string& name, const std::string& binName) const;
  std::string glbBytes() const;
  std::string writeGlb(const TempDir& dir, const std::string& name) const;
};

// Triangle normal from its corner positions (counter-clockwise front face), unnormalized.
glm::vec3 geometricNormal(const std::vector<glm::vec3>& positions, const glm::uvec3& t);

}  // namespace ht::test
