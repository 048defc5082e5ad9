// output_paths.cpp - see output_paths.h.
#include "cli/output_paths.h"

#include <cctype>

namespace ht::cli {
namespace {

// "builtin:NAME" -> NAME; a path -> its stem; anything else unchanged.
std::string baseName(const std::string& spec) {
  const std::string prefix = "builtin:";
  if (spec.rfind(prefix, 0) == 0) return spec.substr(prefix.size());
  const std::filesystem::path path(spec);
  return path.has_stem() ? path.stem().string() : spec;
}

}  // namespace

std::string fileNameToken(const std::string& spec) {
  std::string token;
  for (unsigned char c : baseName(spec)) {
    const bool keep = std::isalnum(c) || c == '-' || c == '_';
    const char out = keep ? char(std::tolower(c)) : '_';
    if (out == '_' && !token.empty() && token.back() == '_') continue;
    token += out;
  }
  while (!token.empty() && token.back() == '_') token.pop_back();
  while (!token.empty() && token.front() == '_') token.erase(token.begin());
  return token.empty() ? "unnamed" : token;
}

OutputPaths resolveOutputPaths(const RenderOptions& options, const std::string& displayName) {
  if (options.png || options.exr) return {options.png, options.exr};
  const std::string stem = fileNameToken(displayName) + "_" + fileNameToken(options.sceneSpec);
  return {options.outDir / (stem + ".png"), options.outDir / (stem + ".exr")};
}

}  // namespace ht::cli
