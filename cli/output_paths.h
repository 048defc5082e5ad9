// output_paths.h - where `holotrace render` writes its images.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "cli/render_options.h"

namespace ht::cli {

struct OutputPaths {
  std::optional<std::filesystem::path> png;
  std::optional<std::filesystem::path> exr;
};

// A file-name-safe token: lower case, [a-z0-9_-] kept, everything else -> '_', runs collapsed.
// "builtin:showcase" -> "showcase"; "/data/My Bunny.glb" -> "my_bunny".
std::string fileNameToken(const std::string& spec);

// With -o and/or --exr: exactly those. With neither: <outDir>/<display>_<scene>.png and .exr.
OutputPaths resolveOutputPaths(const RenderOptions& options, const std::string& displayName);

}  // namespace ht::cli
