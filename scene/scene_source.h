// scene_source.h - the bytes a scene is loaded from, read once up front: the main file and every external file a
// .gltf/.glb references (buffers and images by URI). The loaders parse these bytes and never open a path again, so
// the file that was checked is the file that is loaded (no symlink swap in between), and a cache key over the
// source covers every byte loaded (docs/SERVICE.md §6 "Scene files").
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "common/error.h"
#include "scene/scene_limits.h"

namespace ht {

struct SceneSource {
  std::string name;   // the path as given (errors; the extension picks the loader); never reopened
  std::string bytes;  // the main file
  std::map<std::string, std::string> externals;         // URI as tinygltf decodes it -> the file's bytes
  std::map<std::string, std::string> externalProblems;  // URI -> why it could not be read (reported by the loader)
};

// A path that leads out of the directory it must stay beneath: "..", an absolute path, a symlink out.
class SceneOutsideRoot : public SceneError {
 public:
  using SceneError::SceneError;
};

// Opens `relative` beneath `root` once (openat2 RESOLVE_BENEATH; on kernels without openat2, component by component
// with O_NOFOLLOW, so no symlink at all), reads it, and for .gltf/.glb every external URI beneath the scene file's
// folder. All files together are capped at `maxBytes` (SceneLimitExceeded). Throws SceneOutsideRoot / SceneError.
SceneSource readSceneSourceBeneath(const std::filesystem::path& root, const std::string& relative,
                                   std::uint64_t maxBytes);

// The CLI's form: `path` anywhere, external files confined to its folder as above.
SceneSource readSceneSource(const std::string& path, std::uint64_t maxBytes = limits::kMaxFileBytes);

}  // namespace ht
