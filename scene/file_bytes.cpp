// file_bytes.cpp - whole-file reads for the scene loaders.
#include "scene/file_bytes.h"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "common/error.h"
#include "scene/scene_limits.h"

namespace ht {

std::string readSceneFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw SceneError(path, "file not found (check the path and the working directory)");
  if (!fs::is_regular_file(status)) throw SceneError(path, "not a regular file (pass a scene file, not a directory)");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw SceneError(path, "cannot determine the file size (" + ec.message() + ")");
  if (size > limits::kMaxFileBytes)
    throw SceneError(path, "file is " + std::to_string(size) + " bytes, more than the limit of " +
                               std::to_string(limits::kMaxFileBytes) + " (split or simplify the scene)");

  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, "cannot open the file for reading (check its permissions)");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (in.gcount() != static_cast<std::streamsize>(size))
    throw SceneError(path, "read only " + std::to_string(in.gcount()) + " of " + std::to_string(size) +
                               " bytes (the file changed while loading, or a read error occurred)");
  return bytes;
}

}  // namespace ht
