// image_file_writer.h - writes a rendered frame (linear float RGBA, row 0 = top) to PNG or OpenEXR.
// OpenImageIO is used only here (and in the CLI's tests), never in the core libraries.
//
// Files appear atomically: the image is written to a temporary file in the target directory and renamed
// into place. Any failure throws ht::IoError naming the path and the reason, and leaves no file behind.
#pragma once
#include <string>
#include <utility>
#include <vector>
#include <cstdint>
#include <filesystem>
#include <span>

namespace ht::cli {

enum class ImageFormat {
  Png8Srgb,   // 8-bit RGBA PNG: colour through the sRGB OETF, alpha linear; clamped to [0, 1], rounded
  ExrHalf,    // OpenEXR, linear, 16-bit half RGBA, ZIP compression
  ExrFloat,   // OpenEXR, linear, 32-bit float RGBA, ZIP compression
};

struct RgbaImageView {
  std::uint32_t width = 0, height = 0;
  std::span<const float> rgba;  // width * height * 4 floats, row 0 = top
};

// Text attributes stored in the file (PNG tEXt chunks, EXR string attributes), e.g. {"ImageDescription", json}.
using ImageAttributes = std::vector<std::pair<std::string, std::string>>;

// Writes `image` to `path` in `format`, creating the parent directory if needed.
void writeImageFile(const std::filesystem::path& path, const RgbaImageView& image, ImageFormat format,
                    const ImageAttributes& attributes = {});

// One OpenEXR file holding several views of the same size (OpenEXR multi-view convention, "Storing Multi-View Images
// in OpenEXR Files", Kainz & Bogart): the `multiView` string-vector attribute lists `viewNames` (the first is the
// default view) and view k's channels are named "<name>.R/G/B/A". `rgba` holds the views one after the other, each
// width * height * 4 floats with row 0 = top. `format` must be ExrHalf or ExrFloat. encode...() returns the file's
// bytes (the daemon's captures), write...() writes them atomically.
std::vector<std::uint8_t> encodeMultiViewExr(std::uint32_t width, std::uint32_t height, std::span<const float> rgba,
                                             const std::vector<std::string>& viewNames, ImageFormat format,
                                             const ImageAttributes& attributes = {});
void writeMultiViewExr(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                       std::span<const float> rgba, const std::vector<std::string>& viewNames, ImageFormat format,
                       const ImageAttributes& attributes = {});

}  // namespace ht::cli
