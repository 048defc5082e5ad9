// gltf_file.h - (internal to ht_scene) reading a .gltf/.glb file into a tinygltf::Model safely.
//
// Before tinygltf sees the bytes: the GLB container is validated (header, chunk lengths), the JSON is parsed
// once to refuse non-glTF-2.0 files and unsupported `extensionsRequired` with a clear message, external files come
// only from the SceneSource (read beforehand, confined to the scene's folder with a size cap: no `wordexp`, no `..`
// escapes, no second open), and images are checked to be PNG/JPEG no larger than limits::kMaxImageDimension before
// they are decoded (docs/SERVICE.md §6).
#pragma once
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene/scene_limits.h"
#include "scene/scene_source.h"

namespace ht {

// Extensions whose meaning the loader implements; any other name in `extensionsRequired` is refused.
const std::vector<std::string>& supportedGltfExtensions();

struct GltfDocument {
  tinygltf::Model model;
  std::vector<std::string> warnings;  // from tinygltf and the GLB checks
};

// Throws SceneError(source.name, ...) for every problem.
// `limits`: the node count (from the JSON, before tinygltf allocates) and the texture pixels (from each image's
// header, before decoding) are refused as SceneLimitExceeded.
GltfDocument readGltfDocument(const SceneSource& source, const SceneLimits& limits);

// The external URIs (buffers, images; not data: URIs) of a .gltf/.glb, decoded as tinygltf looks them up. Malformed
// files give an empty list (readGltfDocument reports what is wrong).
std::vector<std::string> gltfExternalUris(const std::string& path, const std::string& bytes);

}  // namespace ht
