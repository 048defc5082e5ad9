// scene_test_util.cpp - see scene_test_util.h.
#include "scene_test_util.h"

#include <atomic>
#include <fstream>
#include <random>

namespace ht::test {

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  std::random_device rd;
  path_ = std::filesystem::temp_directory_path() /
          ("ht_scene_test_" + std::to_string(rd()) + "_" + std::to_string(counter++));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::string TempDir::write(const std::string& name, const std::string& bytes) const {
  const std::string p = file(name);
  std::ofstream out(p, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return p;
}

// RFC 4648 §4 base64 alphabet with '=' padding.
std::string base64(const std::string& bytes) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16 |
                            std::uint32_t(std::uint8_t(bytes[i + 1])) << 8 | std::uint8_t(bytes[i + 2]);
    for (int k = 3; k >= 0; --k) out += abc[(v >> (6 * k)) & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (rest == 2) v |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    out += abc[(v >> 18) & 63];
    out += abc[(v >> 12) & 63];
    out += rest == 2 ? abc[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

namespace {

void putBe32(std::string& s, std::uint32_t v) {
  for (int k = 3; k >= 0; --k) s += static_cast<char>((v >> (8 * k)) & 0xFF);
}
void putLe32(std::string& s, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) s += static_cast<char>((v >> (8 * k)) & 0xFF);
}

// CRC-32 (ISO 3309, reflected polynomial 0xEDB88320) as used by PNG chunks.
std::uint32_t crc32(const std::string& data) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (unsigned char byte : data) {
    c ^= byte;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

// Adler-32 (RFC 1950 §8) over the uncompressed data, trailing the zlib stream.
std::uint32_t adler32(const std::string& data) {
  std::uint32_t a = 1, b = 0;
  for (unsigned char byte : data) {
    a = (a + byte) % 65521u;
    b = (b + a) % 65521u;
  }
  return b << 16 | a;
}

void pngChunk(std::string& png, const char* type, const std::string& data) {
  putBe32(png, static_cast<std::uint32_t>(data.size()));
  const std::string typed = std::string(type, 4) + data;
  png += typed;
  putBe32(png, crc32(typed));
}

// zlib stream (RFC 1950) of stored deflate blocks (RFC 1951 §3.2.4, BTYPE = 00).
std::string zlibStored(const std::string& raw) {
  std::string z = "\x78\x01";
  std::size_t pos = 0;
  do {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - pos);
    const bool last = pos + n == raw.size();
    z += static_cast<char>(last ? 1 : 0);
    z += static_cast<char>(n & 0xFF);
    z += static_cast<char>(n >> 8);
    z += static_cast<char>(~n & 0xFF);
    z += static_cast<char>((~n >> 8) & 0xFF);
    z += raw.substr(pos, n);
    pos += n;
  } while (pos < raw.size());
  putBe32(z, adler32(raw));
  return z;
}

}  // namespace

std::string encodePng(std::uint32_t width, std::uint32_t height, int channels,
                      const std::vector<std::uint8_t>& pixels) {
  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  putBe32(ihdr, width);
  putBe32(ihdr, height);
  ihdr += std::string{'\x08', static_cast<char>(channels == 4 ? 6 : 2), '\0', '\0', '\0'};
  pngChunk(png, "IHDR", ihdr);
  std::string raw;
  const std::size_t rowBytes = std::size_t{width} * static_cast<std::size_t>(channels);
  for (std::uint32_t y = 0; y < height; ++y) {
    raw += '\0';  // filter type None
    raw.append(reinterpret_cast<const char*>(pixels.data()) + y * rowBytes, rowBytes);
  }
  pngChunk(png, "IDAT", zlibStored(raw));
  pngChunk(png, "IEND", "");
  return png;
}

GltfBuilder::GltfBuilder() { doc["asset"] = {{"version", "2.0"}, {"generator", "holotrace scene tests"}}; }

int GltfBuilder::addBufferView(const std::string& bytes, std::size_t byteStride) {
  while (bin.size() % 4 != 0) bin += '\0';
  nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}};
  if (byteStride) view["byteStride"] = byteStride;
  bin += bytes;
  doc["bufferViews"].push_back(view);
  return static_cast<int>(doc["bufferViews"].size() - 1);
}

int GltfBuilder::addAccessor(int bufferView, int componentType, std::size_t count, const std::string& type,
                             bool normalized, std::size_t byteOffset) {
  nlohmann::json a = {{"bufferView", bufferView}, {"componentType", componentType}, {"count", count}, {"type", type}};
  if (normalized) a["normalized"] = true;
  if (byteOffset) a["byteOffset"] = byteOffset;
  doc["accessors"].push_back(a);
  return static_cast<int>(doc["accessors"].size() - 1);
}

int GltfBuilder::addPositions(const std::vector<glm::vec3>& p) {
  std::vector<float> flat;
  for (const glm::vec3& v : p) flat.insert(flat.end(), {v.x, v.y, v.z});
  return addData(flat, kFloat, "VEC3", 3);
}

int GltfBuilder::addNormals(const std::vector<glm::vec3>& n) { return addPositions(n); }

int GltfBuilder::addMesh(const nlohmann::json& primitive) {
  doc["meshes"].push_back({{"primitives", nlohmann::json::array({primitive})}});
  return static_cast<int>(doc["meshes"].size() - 1);
}

int GltfBuilder::addNode(const nlohmann::json& node) {
  doc["nodes"].push_back(node);
  return static_cast<int>(doc["nodes"].size() - 1);
}

void GltfBuilder::setScene(const std::vector<int>& rootNodes) {
  doc["scenes"] = nlohmann::json::array({{{"nodes", rootNodes}}});
  doc["scene"] = 0;
}

std::string GltfBuilder::writeGltf(const TempDir& dir, const std::string& name) const {
  nlohmann::json d = doc;
  d["buffers"] = nlohmann::json::array(
      {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
  return dir.write(name, d.dump(2));
}

std::string GltfBuilder::writeGltfExternal(const TempDir& dir, const std::string& name,
                                           const std::string& binName) const {
  nlohmann::json d = doc;
  d["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}, {"uri", binName}}});
  dir.write(binName, bin);
  return dir.write(name, d.dump(2));
}

// GLB (glTF 2.0 spec, "GLB File Format Specification"): 12-byte header, JSON chunk padded with spaces,
// BIN chunk padded with zeros, both to 4 bytes.
std::string GltfBuilder::glbBytes() const {
  nlohmann::json d = doc;
  d["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
  std::string json = d.dump();
  while (json.size() % 4 != 0) json += ' ';
  std::string payload = bin;
  while (payload.size() % 4 != 0) payload += '\0';
  std::string glb;
  putLe32(glb, 0x46546C67u);
  putLe32(glb, 2);
  putLe32(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + payload.size()));
  putLe32(glb, static_cast<std::uint32_t>(json.size()));
  putLe32(glb, 0x4E4F534Au);
  glb += json;
  putLe32(glb, static_cast<std::uint32_t>(payload.size()));
  putLe32(glb, 0x004E4942u);
  glb += payload;
  return glb;
}

std::string GltfBuilder::writeGlb(const TempDir& dir, const std::string& name) const {
  return dir.write(name, glbBytes());
}

glm::vec3 geometricNormal(const std::vector<glm::vec3>& p, const glm::uvec3& t) {
  return glm::cross(p[t.y] - p[t.x], p[t.z] - p[t.x]);
}

}  // namespace ht::test
