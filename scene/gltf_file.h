// gltf_file.h - (internal to ht_scene) reading a .gltf/.glb file into a tinygltf::Model safely.
//
// Before tinygltf sees the bytes: the GLB container is validated (header, chunk lengths), the JSON is parsed
// once to refuse non-glTF-2.0 files and unsupported `extensionsRequired` with a clear message, file access
// is confined to the scene's folder with a size cap (no `wordexp`, no `..` escapes), and images are checked
// to be PNG/JPEG no larger than limits::kMaxImageDimension before they are decoded (docs/SERVICE.md §6).
#pragma once
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace ht {

// Extensions whose meaning the loader implements; any other name in `extensionsRequired` is refused.
const std::vector<std::string>& supportedGltfExtensions();

struct GltfDocument {
  tinygltf::Model model;
  std::vector<std::string> warnings;  // from tinygltf and the GLB checks
};

// Throws SceneError(path, ...) for every problem.
GltfDocument readGltfDocument(const std::string& path);

}  // namespace ht
