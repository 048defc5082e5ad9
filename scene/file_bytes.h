// file_bytes.h - reading a whole scene file with a size cap; failures are SceneErrors naming the file.
#pragma once
#include <string>

namespace ht {

// Reads `path` into a string. Throws SceneError(path, ...) when it does not exist, is not a regular file,
// cannot be read, or is larger than limits::kMaxFileBytes.
std::string readSceneFile(const std::string& path);

}  // namespace ht
