// frame_file_names.cpp - see frame_file_names.h.
#include "frame_io/frame_file_names.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "common/error.h"

namespace ht::frame_io {
namespace {

bool statesLayout(const std::string& fileName, const QuiltLayout& layout) {
  try {
    const QuiltName name = parseQuiltName(fileName);
    return name.columns == layout.columns && name.rows == layout.rows && name.aspect == layout.aspect;
  } catch (const ConfigError&) {
    return false;  // no tag, or not a valid one
  }
}

}  // namespace

std::string viewNumber(std::uint32_t view, std::uint32_t views) {
  const std::size_t digits = std::max<std::size_t>(2, std::to_string(views > 0 ? views - 1 : 0).size());
  const std::string number = std::to_string(view);
  return std::string(digits - std::min(digits, number.size()), '0') + number;
}

std::string multiViewName(std::uint32_t view, std::uint32_t views) { return "view" + viewNumber(view, views); }

std::string captureFrameStem(const std::string& name, std::uint32_t index) {
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "_f%04u", index);
  return name + suffix;
}

std::string withSuffix(const std::string& fileName, const std::string& suffix) {
  const std::filesystem::path path(fileName);
  return path.stem().string() + suffix + path.extension().string();
}

std::string withExtension(const std::string& fileName, const std::string& extension) {
  return std::filesystem::path(fileName).replace_extension(extension).string();
}

std::string quiltFileName(const std::string& fileName, const QuiltLayout& layout) {
  if (statesLayout(fileName, layout)) return fileName;
  return withSuffix(fileName, formatQuiltName(layout.columns, layout.rows, layout.aspect));
}

}  // namespace ht::frame_io
