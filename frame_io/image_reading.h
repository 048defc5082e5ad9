// image_reading.h - PNG and OpenEXR files (or their bytes) read into linear float RGBA, row 0 = top: quilts and
// views for `holotrace interleave`, frames read back by tests.
//
// Values: 8- and 16-bit integer images are sRGB-encoded (PNG's default colour space; a file OpenImageIO reports as
// "Linear" is taken as linear) and are decoded through the sRGB EOTF (common/srgb.h); half and float images are linear
// and read unchanged. Alpha is linear and never associated on read. Channels: R, G, B and A by name (grey "Y" fills
// R, G, B), else by position (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA); a missing alpha reads as 1. A multiView EXR
// (frame_io/image_encoding.h) gives every view, named channels "<view>.R" ... (the default view may also use bare
// "R" ...).
//
// Bad input never crashes or allocates without bound: the size is checked from the header before any pixel memory
// (at most kMaxImageSide per side and kMaxImageValues floats in all); every failure is an IoError naming the file and
// what is wrong.
#pragma once
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "common/image_limits.h"
#include "frame_io/frame_images.h"
#include "frame_io/image_encoding.h"

namespace ht::frame_io {

inline constexpr std::uint64_t kMaxImageValues = std::uint64_t(1) << 28;  // floats: 1 GiB, an 8192^2 RGBA quilt

enum class SampleType { UInt8, UInt16, Half, Float, Other };

// What a file's header says.
struct ImageHeader {
  std::uint32_t width = 0, height = 0, views = 1;
  std::vector<std::string> viewNames;     // a multiView EXR's views (view 0 = the default view); else empty
  std::vector<std::string> channelNames;  // as stored in the file
  std::vector<SampleType> channelTypes;   // per channel, as stored
  ImageAttributes attributes;             // the file's string attributes (ImageDescription, Software, ...)

  // The value of string attribute `name`, or "" if the file has none.
  std::string attribute(const std::string& name) const;
};

struct ImageFile : ImageHeader {
  std::vector<float> rgba;  // linear RGBA, view after view, row 0 = top

  FrameImages frame() const { return {width, height, views, rgba}; }
};

// The header only (no pixel memory). Throws IoError naming `path`.
ImageHeader readImageHeader(const std::filesystem::path& path);

// Throws IoError naming `path`.
ImageFile readImageFile(const std::filesystem::path& path);

// The same from file bytes in memory; `fileName` names them in errors and its extension picks the reader (.png,
// .exr). Throws IoError.
ImageFile decodeImage(std::span<const std::uint8_t> bytes, const std::string& fileName);

}  // namespace ht::frame_io
