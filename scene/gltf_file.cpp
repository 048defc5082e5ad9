// gltf_file.cpp - GLB container checks, JSON pre-checks, confined file access and checked image decoding
// around tinygltf 2.7.0 (Debian 12; known issues listed in docs/SERVICE.md §6).
#include "scene/gltf_file.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "scene/file_bytes.h"
#include "scene/scene_limits.h"

namespace ht {
namespace {

namespace fs = std::filesystem;

// ---- GLB container (glTF 2.0 spec, "GLB File Format Specification") --------------------------------------------
// 12-byte header: uint32 magic 0x46546C67 ("glTF"), uint32 version (2), uint32 total length; then chunks
// of uint32 chunkLength, uint32 chunkType, chunkData: first JSON (0x4E4F534A), then optionally BIN
// (0x004E4942). All little-endian.
constexpr std::uint32_t kGlbMagic = 0x46546C67u;
constexpr std::uint32_t kChunkJson = 0x4E4F534Au;
constexpr std::uint32_t kChunkBin = 0x004E4942u;
constexpr std::size_t kGlbHeaderBytes = 12, kChunkHeaderBytes = 8;

std::uint32_t readLe32(const std::string& bytes, std::size_t offset) {
  unsigned char b[4];
  std::memcpy(b, bytes.data() + offset, 4);
  return std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 | std::uint32_t{b[3]} << 24;
}

bool hasGlbMagic(const std::string& bytes) { return bytes.size() >= 4 && readLe32(bytes, 0) == kGlbMagic; }

struct GlbLayout {
  std::size_t length = 0;  // bytes of the GLB (header's total length)
  std::string_view json;   // JSON chunk content
};

GlbLayout checkGlbLayout(const std::string& path, const std::string& bytes, std::vector<std::string>& warnings) {
  const auto truncated = [&](const std::string& what) {
    return SceneError(path, "truncated GLB: " + what + " (the file is incomplete; download or export it again)");
  };
  if (bytes.size() < kGlbHeaderBytes + kChunkHeaderBytes)
    throw truncated("only " + std::to_string(bytes.size()) + " bytes, a GLB header and JSON chunk header need 20");
  const std::uint32_t version = readLe32(bytes, 4);
  if (version != 2)
    throw SceneError(path, "GLB container version " + std::to_string(version) +
                               " is not supported (only glTF 2.0 binary files; convert glTF 1.0 files to 2.0)");
  GlbLayout layout;
  layout.length = readLe32(bytes, 8);
  if (layout.length > bytes.size())
    throw truncated("the header declares " + std::to_string(layout.length) + " bytes but the file has " +
                    std::to_string(bytes.size()));
  if (layout.length < bytes.size())
    warnings.push_back("GLB header declares " + std::to_string(layout.length) + " bytes; ignoring " +
                       std::to_string(bytes.size() - layout.length) + " trailing bytes");
  if (layout.length < kGlbHeaderBytes + kChunkHeaderBytes)
    throw truncated("the header declares only " + std::to_string(layout.length) + " bytes");

  const std::size_t jsonLength = readLe32(bytes, 12);
  if (readLe32(bytes, 16) != kChunkJson)
    throw SceneError(path, "the first GLB chunk is not JSON (the file is corrupt; re-export it)");
  if (jsonLength > layout.length - kGlbHeaderBytes - kChunkHeaderBytes)
    throw truncated("the JSON chunk declares " + std::to_string(jsonLength) + " bytes but only " +
                    std::to_string(layout.length - 20) + " follow");
  layout.json = std::string_view(bytes).substr(20, jsonLength);

  // Optional BIN chunk after the (4-byte padded) JSON chunk.
  const std::size_t binHeader = 20 + ((jsonLength + 3) / 4) * 4;
  if (binHeader + kChunkHeaderBytes <= layout.length) {
    const std::size_t binLength = readLe32(bytes, binHeader);
    if (readLe32(bytes, binHeader + 4) == kChunkBin && binLength > layout.length - binHeader - kChunkHeaderBytes)
      throw truncated("the BIN chunk declares " + std::to_string(binLength) + " bytes but only " +
                      std::to_string(layout.length - binHeader - kChunkHeaderBytes) + " follow");
  }
  return layout;
}

// ---- JSON pre-checks -------------------------------------------------------------------------------------

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

[[noreturn]] void refuseRequiredExtension(const std::string& path, const std::string& name) {
  if (name == "KHR_draco_mesh_compression")
    throw SceneError(path,
                     "requires KHR_draco_mesh_compression: Draco-compressed meshes are not supported "
                     "(decompress the file first, e.g. with glTF-Transform: read it with the draco3d decoder "
                     "registered, dispose KHR_draco_mesh_compression and write it again; or re-export "
                     "without Draco compression)");
  if (name == "EXT_meshopt_compression" || name == "KHR_meshopt_compression")
    throw SceneError(path, "requires " + name +
                               ": meshoptimizer-compressed buffers are not supported "
                               "(re-export without meshopt compression, e.g. glTF-Transform without --meshopt)");
  throw SceneError(path, "requires the glTF extension " + name + ", which holotrace does not support (supported: " +
                             joined(supportedGltfExtensions()) + "; re-export the file without it)");
}

bool isSupported(const std::string& name) {
  const auto& s = supportedGltfExtensions();
  return std::find(s.begin(), s.end(), name) != s.end();
}

// Deepest array/object nesting, measured iteratively. tinygltf converts `extras`/`extensions` with
// recursive functions, so a hostile file nesting thousands of levels could exhaust the stack there.
std::size_t nestingDepth(const nlohmann::json& root) {
  std::size_t deepest = 0;
  std::vector<std::pair<const nlohmann::json*, std::size_t>> stack{{&root, 1}};
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    if (node->is_structured())
      for (const auto& child : *node) stack.push_back({&child, depth + 1});
  }
  return deepest;
}

constexpr std::size_t kMaxJsonDepth = 64;

void checkJson(const std::string& path, std::string_view text, std::vector<std::string>& warnings) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::exception& e) {
    throw SceneError(path, std::string("not valid JSON: ") + e.what() +
                               " (a .gltf file must be glTF 2.0 JSON; check the file is not truncated or binary)");
  }
  if (!doc.is_object()) throw SceneError(path, "the JSON top level is not an object (not a glTF 2.0 file)");
  if (nestingDepth(doc) > kMaxJsonDepth)
    throw SceneError(path, "JSON nesting deeper than " + std::to_string(kMaxJsonDepth) +
                               " levels (not a plausible glTF file; check where it came from)");
  const auto asset = doc.find("asset");
  if (asset == doc.end() || !asset->is_object() || !asset->contains("version") || !(*asset)["version"].is_string())
    throw SceneError(path, "no 'asset.version': not a glTF 2.0 file (glTF 1.0 files must be converted to 2.0)");
  const std::string version = (*asset)["version"].get<std::string>();
  if (version.rfind("2.", 0) != 0)
    throw SceneError(path, "glTF version '" + version + "' is not supported (only 2.x; convert the file to glTF 2.0)");

  if (const auto req = doc.find("extensionsRequired"); req != doc.end()) {
    if (!req->is_array()) throw SceneError(path, "'extensionsRequired' is not an array of names (fix the file)");
    for (const auto& name : *req) {
      if (!name.is_string()) throw SceneError(path, "'extensionsRequired' holds a non-string entry (fix the file)");
      if (!isSupported(name.get<std::string>())) refuseRequiredExtension(path, name.get<std::string>());
    }
  }
  if (const auto used = doc.find("extensionsUsed"); used != doc.end() && used->is_array())
    for (const auto& name : *used)
      if (name.is_string() && !isSupported(name.get<std::string>()))
        warnings.push_back("optional extension " + name.get<std::string>() + " is ignored");
}

// ---- confined file access (replaces tinygltf's default callbacks: no wordexp, no reads outside the folder)

struct FolderRoot {
  fs::path root;  // canonical scene folder
};

bool insideRoot(const std::string& file, const FolderRoot& r) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::path(file), ec);
  if (ec) return false;
  const fs::path rel = p.lexically_relative(r.root);
  return !rel.empty() && rel != "." && *rel.begin() != "..";
}

bool fileExistsInRoot(const std::string& file, void* user) {
  std::error_code ec;
  return insideRoot(file, *static_cast<FolderRoot*>(user)) && fs::is_regular_file(file, ec);
}

std::string expandNothing(const std::string& file, void*) { return file; }

bool readFileInRoot(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
  if (!insideRoot(file, *static_cast<FolderRoot*>(user))) {
    if (err) *err += "'" + file + "' is outside the scene folder; external files must sit next to the .gltf\n";
    return false;
  }
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec || size > limits::kMaxFileBytes) {
    if (err)
      *err += "'" + file + "' is unreadable or larger than " + std::to_string(limits::kMaxFileBytes) + " bytes\n";
    return false;
  }
  std::ifstream in(file, std::ios::binary);
  out->resize(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size));
  if (!in || in.gcount() != static_cast<std::streamsize>(size)) {
    if (err) *err += "failed to read '" + file + "'\n";
    return false;
  }
  return true;
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is disabled\n";
  return false;
}

// ---- image size sniffing before decoding -----------------------------------------------------------------

struct ImageSize {
  std::uint32_t width = 0, height = 0;
  bool known = false;
};

std::uint32_t be16(const unsigned char* p) { return std::uint32_t{p[0]} << 8 | p[1]; }
std::uint32_t be32(const unsigned char* p) { return be16(p) << 16 | be16(p + 2); }

// PNG: 8-byte signature, then the IHDR chunk (length, "IHDR", width, height big-endian) (PNG spec,
// W3C/ISO 15948: "PNG signature" and "IHDR Image header").
ImageSize pngSize(const unsigned char* b, std::size_t n) {
  static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (n < 24 || std::memcmp(b, sig, 8) != 0 || std::memcmp(b + 12, "IHDR", 4) != 0) return {};
  return {be32(b + 16), be32(b + 20), true};
}

// JPEG: SOI (FFD8), then marker segments FFxx + big-endian length; a start-of-frame marker SOF0..SOF15
// (C0-CF except DHT C4, JPG C8, DAC CC) holds precision(1), height(2), width(2) (ITU-T T.81 §B.1.1.3, B.2.2).
ImageSize jpegSize(const unsigned char* b, std::size_t n) {
  if (n < 4 || b[0] != 0xFF || b[1] != 0xD8) return {};
  std::size_t pos = 2;
  while (pos + 4 <= n) {
    if (b[pos] != 0xFF) return {};
    const unsigned char marker = b[pos + 1];
    if (marker == 0xFF) {
      ++pos;
      continue;
    }  // fill byte
    if ((marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {
      pos += 2;
      continue;
    }                                                 // no length field
    if (marker == 0xDA || marker == 0xD9) return {};  // scan/end before a frame
    const std::size_t length = be16(b + pos + 2);
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      if (pos + 9 > n) return {};
      return {be16(b + pos + 7), be16(b + pos + 5), true};
    }
    if (length < 2) return {};
    pos += 2 + length;
  }
  return {};
}

bool decodeImageChecked(tinygltf::Image* image, int index, std::string* err, std::string* warn,
                        const unsigned char* bytes, std::size_t size) {
  const auto fail = [&](const std::string& why) {
    if (err) *err += "image " + std::to_string(index) + ": " + why + "\n";
    return false;
  };
  ImageSize dims = pngSize(bytes, size);
  if (!dims.known) dims = jpegSize(bytes, size);
  if (!dims.known)
    return fail("not a PNG or JPEG image (glTF 2.0 allows image/png and image/jpeg; convert the texture)");
  if (dims.width == 0 || dims.height == 0 || dims.width > limits::kMaxImageDimension ||
      dims.height > limits::kMaxImageDimension)
    return fail(std::to_string(dims.width) + " x " + std::to_string(dims.height) + " pixels, outside 1.." +
                std::to_string(limits::kMaxImageDimension) + " per side (downscale the texture)");
  if (size > static_cast<std::size_t>(INT_MAX)) return fail("encoded image larger than 2 GiB");
  return tinygltf::LoadImageData(image, index, err, warn, 0, 0, bytes, static_cast<int>(size), nullptr);
}

// tinygltf calls this for every image. Images stored in a bufferView are decoded later by
// decodeBufferViewImages(): tinygltf 2.7.0 passes `&buffer.data[bufferView.byteOffset]` with
// `bufferView.byteLength` without checking that range against the buffer.
bool imageLoaderCallback(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int, int,
                         const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;
  if (size <= 0) {
    if (err) *err += "image " + std::to_string(index) + " is empty\n";
    return false;
  }
  return decodeImageChecked(image, index, err, warn, bytes, static_cast<std::size_t>(size));
}

void decodeBufferViewImages(const std::string& path, tinygltf::Model& model, std::vector<std::string>& warnings) {
  for (std::size_t i = 0; i < model.images.size(); ++i) {
    tinygltf::Image& image = model.images[i];
    if (image.bufferView < 0 || !image.image.empty()) continue;
    const std::string what = "image " + std::to_string(i);
    if (static_cast<std::size_t>(image.bufferView) >= model.bufferViews.size())
      throw SceneError(path,
                       what + " refers to missing bufferView " + std::to_string(image.bufferView) + " (fix the file)");
    const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(image.bufferView)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
      throw SceneError(
          path, what + ": its bufferView refers to missing buffer " + std::to_string(view.buffer) + " (fix the file)");
    const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteLength == 0 || view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
      throw SceneError(path, what + ": bufferView bytes [" + std::to_string(view.byteOffset) + ", +" +
                                 std::to_string(view.byteLength) + ") exceed its buffer of " +
                                 std::to_string(data.size()) + " bytes (the file is truncated or corrupt)");
    std::string err, warn;
    const bool ok =
        decodeImageChecked(&image, static_cast<int>(i), &err, &warn, data.data() + view.byteOffset, view.byteLength);
    if (!warn.empty()) warnings.push_back(warn);
    if (!err.empty() && err.back() == '\n') err.pop_back();
    if (!ok) throw SceneError(path, err.empty() ? what + " cannot be decoded (re-export it as PNG or JPEG)" : err);
  }
}

}  // namespace

const std::vector<std::string>& supportedGltfExtensions() {
  static const std::vector<std::string> names{"KHR_lights_punctual", "KHR_materials_emissive_strength",
                                              "KHR_materials_ior", "KHR_materials_transmission",
                                              "KHR_mesh_quantization"};
  return names;
}

GltfDocument readGltfDocument(const std::string& path) {
  const std::string bytes = readSceneFile(path);
  GltfDocument doc;
  const bool glb = hasGlbMagic(bytes);
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".glb" && !glb)
    throw SceneError(path, "not a GLB file: the 'glTF' magic is missing (rename a JSON file to .gltf, or re-export)");

  std::size_t length = bytes.size();
  std::string_view jsonText = bytes;
  if (glb) {
    const GlbLayout layout = checkGlbLayout(path, bytes, doc.warnings);
    length = layout.length;
    jsonText = layout.json;
  }
  checkJson(path, jsonText, doc.warnings);

  std::error_code ec;
  FolderRoot root{fs::weakly_canonical(fs::absolute(fs::path(path)).parent_path(), ec)};
  if (ec) throw SceneError(path, "cannot resolve the scene folder (" + ec.message() + ")");
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&fileExistsInRoot, &expandNothing, &readFileInRoot, &refuseWrite, &root});
  loader.SetImageLoader(&imageLoaderCallback, nullptr);

  std::string err, warn;
  const std::string baseDir = root.root.string();
  const bool ok =
      glb ? loader.LoadBinaryFromMemory(&doc.model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                        static_cast<unsigned int>(length), baseDir)
          : loader.LoadASCIIFromString(&doc.model, &err, &warn, bytes.data(), static_cast<unsigned int>(length),
                                       baseDir);
  if (!warn.empty()) doc.warnings.push_back(warn);
  if (!ok) {
    if (!err.empty() && err.back() == '\n') err.pop_back();
    throw SceneError(path, "invalid glTF: " + err + " (check the file with the Khronos glTF-Validator)");
  }
  decodeBufferViewImages(path, doc.model, doc.warnings);
  return doc;
}

}  // namespace ht
