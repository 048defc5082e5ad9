// image_encoding.h - images as PNG or OpenEXR file bytes (linear float RGBA in, row 0 = top). The bytes go wherever
// the caller puts them: an atomic file (frame_io/atomic_output_file.h), the daemon's confined output root, the wire.
//
// Every file is deterministic: the same pixels and attributes give the same bytes (OpenImageIO would stamp EXR files
// with the current time as `capDate`; holotrace stores no date). Colour-space, alpha and software attributes:
//   PNG   8-bit RGBA, colour through the sRGB OETF, alpha linear (frame_io/pixel_encoding.h), unassociated alpha (the
//         stored colour is what was rendered, never divided by alpha), oiio:ColorSpace sRGB, Software "holotrace";
//   EXR   16-bit half or 32-bit float RGBA, linear values unchanged, ZIP compression, oiio:ColorSpace Linear,
//         Software "holotrace".
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "frame_io/frame_images.h"

namespace ht::frame_io {

enum class ImageFormat {
  Png8Srgb,  // 8-bit RGBA PNG, sRGB
  ExrHalf,   // OpenEXR, linear, 16-bit half RGBA, ZIP compression
  ExrFloat,  // OpenEXR, linear, 32-bit float RGBA, ZIP compression
};

// Text attributes stored in the file (PNG tEXt chunks, EXR string attributes), e.g. {"ImageDescription", json}; an
// EXR stores ImageDescription as its standard `comments` attribute.
using ImageAttributes = std::vector<std::pair<std::string, std::string>>;

// The file bytes of one image. Throws IoError for an image whose size does not match its pixels, or when OpenImageIO
// fails (the message names the step and OpenImageIO's reason).
std::vector<std::uint8_t> encodeImage(const RgbaImageView& image, ImageFormat format,
                                      const ImageAttributes& attributes = {});

// An OpenEXR file of arbitrary named channels (ray tables, test files): `values` holds width * height pixels of
// channelNames.size() values each, row 0 = top. `format` must be ExrHalf or ExrFloat (the storage of every channel);
// no channel is treated as alpha and no colour space is stored. Throws IoError as encodeImage.
std::vector<std::uint8_t> encodeExrChannels(std::uint32_t width, std::uint32_t height,
                                            const std::vector<std::string>& channelNames, std::span<const float> values,
                                            ImageFormat format, const ImageAttributes& attributes = {});

// One OpenEXR file holding every view of `frame` (OpenEXR multi-view convention, "Storing Multi-View Images in OpenEXR
// Files", Kainz & Bogart): the `multiView` string-vector attribute lists `viewNames` (the first is the default view)
// and view k's channels are "<name>.R/G/B/A". `format` must be ExrHalf or ExrFloat. Throws IoError as encodeImage.
std::vector<std::uint8_t> encodeMultiViewExr(const FrameImages& frame, const std::vector<std::string>& viewNames,
                                             ImageFormat format, const ImageAttributes& attributes = {});

}  // namespace ht::frame_io
