// image_output.h - one image written to the path a command was given (-o): 8-bit sRGB PNG or linear half-float
// OpenEXR by the path's extension, atomically (frame_io/atomic_output_file.h). `holotrace interleave` and `simulate`.
#pragma once
#include <filesystem>
#include <string>

#include "frame_io/frame_images.h"

namespace ht::cli {

// Throws UsageError ("<command>: option '-o' = ...") unless the path ends in .png or .exr (any case).
void checkImageOutputPath(const std::string& command, const std::filesystem::path& path);

// Encodes and writes the image. Throws IoError naming the path.
void writeImageOutput(const std::filesystem::path& path, const frame_io::RgbaImageView& image);

}  // namespace ht::cli
