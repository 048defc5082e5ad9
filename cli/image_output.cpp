// image_output.cpp - see image_output.h.
#include "cli/image_output.h"

#include <algorithm>
#include <cctype>
#include <vector>

#include "cli/arguments.h"
#include "common/error.h"
#include "frame_io/atomic_output_file.h"
#include "frame_io/image_encoding.h"

namespace ht::cli {
namespace {

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

void checkImageOutputPath(const std::string& command, const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".exr") {
    throw UsageError(usageMessage(command, "option '-o' = '" + path.string() +
                                               "': expected a path ending in .png (8-bit sRGB) or .exr (linear half)"));
  }
}

void writeImageOutput(const std::filesystem::path& path, const frame_io::RgbaImageView& image) {
  const frame_io::ImageFormat format =
      lowerExtension(path) == ".exr" ? frame_io::ImageFormat::ExrHalf : frame_io::ImageFormat::Png8Srgb;
  const std::vector<frame_io::OutputFile> files{{path, frame_io::encodeImage(image, format)}};
  frame_io::writeFilesAtomically(files);
}

}  // namespace ht::cli
