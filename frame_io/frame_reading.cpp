// frame_reading.cpp - see frame_reading.h.
#include "frame_io/frame_reading.h"

#include <string>

#include "common/error.h"
#include "frame_io/frame_file_names.h"
#include "frame_io/image_reading.h"

namespace ht::frame_io {
namespace {

std::string sizeText(std::uint32_t views, std::uint32_t width, std::uint32_t height) {
  return std::to_string(views) + " image(s) of " + std::to_string(width) + "x" + std::to_string(height);
}

[[noreturn]] void throwMismatch(const std::filesystem::path& path, const ImageFile& image, std::uint32_t width,
                                std::uint32_t height, std::uint32_t views) {
  throw IoError("'" + path.string() + "' holds " + sizeText(image.views, image.width, image.height) +
                ", the display shows " + sizeText(views, width, height) +
                (views > 1 ? " (give a multiView EXR, the first of the per-view PNGs x_v" + viewNumber(0, views) +
                                 ".png, or the views stacked top to bottom)"
                           : " (render it for this display)"));
}

// The name of view k's file when `path` names view 0's ("shot_v00.png" -> "shot_v07.png"); empty if it does not.
std::filesystem::path siblingView(const std::filesystem::path& path, std::uint32_t k, std::uint32_t views) {
  const std::string stem = path.stem().string(), first = "_v" + viewNumber(0, views);
  if (stem.size() <= first.size() || stem.compare(stem.size() - first.size(), first.size(), first) != 0) return {};
  const std::string base = stem.substr(0, stem.size() - first.size());
  return path.parent_path() / (base + "_v" + viewNumber(k, views) + path.extension().string());
}

}  // namespace

ReadFrame readFrameViews(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                         std::uint32_t views) {
  ImageFile first = readImageFile(path);
  ReadFrame frame{width, height, views, {}};
  if (first.width == width && first.height == height && first.views == views) {
    frame.rgba = std::move(first.rgba);  // one image, or a multiView EXR with every view
  } else if (first.views == 1 && first.width == width && std::uint64_t(first.height) == std::uint64_t(height) * views) {
    frame.rgba = std::move(first.rgba);  // stacked top to bottom: view after view already
  } else if (first.views == 1 && first.width == width && first.height == height &&
             !siblingView(path, 0, views).empty()) {
    frame.rgba = std::move(first.rgba);
    for (std::uint32_t k = 1; k < views; ++k) {
      const std::filesystem::path next = siblingView(path, k, views);
      const ImageFile view = readImageFile(next);
      if (view.views != 1 || view.width != width || view.height != height) throwMismatch(next, view, width, height, 1);
      frame.rgba.insert(frame.rgba.end(), view.rgba.begin(), view.rgba.end());
    }
  } else {
    throwMismatch(path, first, width, height, views);
  }
  return frame;
}

}  // namespace ht::frame_io
