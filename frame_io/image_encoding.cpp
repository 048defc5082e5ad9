// image_encoding.cpp - see image_encoding.h. Files are encoded into memory through an OpenImageIO IOProxy
// (ImageOutput::set_ioproxy + Filesystem::IOVecOutput, OpenImageIO imageio.h / filesystem.h).
#include "frame_io/image_encoding.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "common/error.h"
#include "frame_io/pixel_encoding.h"

namespace ht::frame_io {
namespace {

constexpr int kChannels = 4;

bool isExr(ImageFormat format) { return format != ImageFormat::Png8Srgb; }

OIIO::TypeDesc storedType(ImageFormat format) {
  return format == ImageFormat::Png8Srgb  ? OIIO::TypeDesc::UINT8
         : format == ImageFormat::ExrHalf ? OIIO::TypeDesc::HALF
                                          : OIIO::TypeDesc::FLOAT;
}

// The attributes every file of `format` carries (colour ones for images, not for other channels), then the caller's.
void addAttributes(OIIO::ImageSpec& spec, ImageFormat format, const ImageAttributes& attributes, bool colour) {
  if (colour) spec.attribute("oiio:ColorSpace", isExr(format) ? "Linear" : "sRGB");
  spec.attribute("Software", "holotrace");
  // Store the colour values exactly as given: without this OIIO would treat them as premultiplied and divide by alpha
  // before writing the (unassociated-alpha) PNG.
  if (colour) spec.attribute("oiio:UnassociatedAlpha", 1);
  if (isExr(format)) {
    spec.attribute("compression", "zip");
    spec.attribute("DateTime", "");  // no capDate of the current time: same pixels, same bytes
  }
  for (const auto& [name, value] : attributes) spec.attribute(name, value);
}

// Runs OpenImageIO's writer for `formatName` on `spec` into memory; `pixels` are of type `dataType`.
std::vector<std::uint8_t> encodeWithOiio(const OIIO::ImageSpec& spec, OIIO::TypeDesc dataType, const void* pixels,
                                         const char* formatName) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto out = OIIO::ImageOutput::create(formatName);
  const auto fail = [&](const char* step) {
    std::string detail = out ? out->geterror() : "";
    if (detail.empty()) detail = OIIO::geterror();
    if (detail.empty()) detail = "unknown OpenImageIO error";
    throw IoError(std::string("cannot encode ") + formatName + ": " + step + ": " + detail);
  };
  if (!out) fail("no OpenImageIO writer");
  if (!out->set_ioproxy(&proxy)) fail("cannot write to memory");
  if (!out->open(std::string("image.") + formatName, spec)) fail("open");
  if (!out->write_image(dataType, pixels)) {
    out->close();
    fail("write");
  }
  if (!out->close()) fail("close");
  return {bytes.begin(), bytes.end()};
}

// An EXR of named channels (interleaved `values`); with `viewNames`, a multi-view colour image carrying the multiView
// attribute, else channels of any meaning (no colour attributes).
std::vector<std::uint8_t> encodeChannels(std::uint32_t width, std::uint32_t height,
                                         const std::vector<std::string>& channelNames, std::span<const float> values,
                                         ImageFormat format, const ImageAttributes& attributes,
                                         const std::vector<std::string>* viewNames) {
  const std::size_t channels = channelNames.size();
  if (width == 0 || height == 0 || channels == 0 || values.size() != std::size_t(width) * height * channels ||
      !isExr(format)) {
    throw IoError("cannot encode an EXR of " + std::to_string(channels) + " channels, " + std::to_string(width) + "x" +
                  std::to_string(height) + " with " + std::to_string(values.size()) + " values as " +
                  (isExr(format) ? "EXR" : "PNG") + ": expected an EXR format and width*height*channels values " +
                  "(a caller bug)");
  }
  OIIO::ImageSpec spec(int(width), int(height), int(channels), storedType(format));
  spec.channelnames = channelNames;
  spec.alpha_channel = -1;  // no channel (or several, one per view) is "the" alpha
  if (viewNames != nullptr) {
    std::vector<const char*> names;
    for (const std::string& name : *viewNames) names.push_back(name.c_str());
    spec.attribute("multiView", OIIO::TypeDesc(OIIO::TypeDesc::STRING, int(names.size())), names.data());
  }
  addAttributes(spec, format, attributes, viewNames != nullptr);
  return encodeWithOiio(spec, OIIO::TypeDesc::FLOAT, values.data(), "exr");
}

}  // namespace

std::vector<std::uint8_t> encodeImage(const RgbaImageView& image, ImageFormat format,
                                      const ImageAttributes& attributes) {
  checkImage(image, "cannot encode an image");
  OIIO::ImageSpec spec(int(image.width), int(image.height), kChannels, storedType(format));
  addAttributes(spec, format, attributes, true);
  if (isExr(format)) return encodeWithOiio(spec, OIIO::TypeDesc::FLOAT, image.rgba.data(), "exr");
  const std::vector<std::uint8_t> codes = encodeRgba8Srgb(image.rgba);
  return encodeWithOiio(spec, OIIO::TypeDesc::UINT8, codes.data(), "png");
}

std::vector<std::uint8_t> encodeExrChannels(std::uint32_t width, std::uint32_t height,
                                            const std::vector<std::string>& channelNames, std::span<const float> values,
                                            ImageFormat format, const ImageAttributes& attributes) {
  return encodeChannels(width, height, channelNames, values, format, attributes, nullptr);
}

std::vector<std::uint8_t> encodeMultiViewExr(const FrameImages& frame, const std::vector<std::string>& viewNames,
                                             ImageFormat format, const ImageAttributes& attributes) {
  checkFrame(frame, "cannot encode a multi-view EXR");
  if (viewNames.size() != frame.views) {
    throw IoError("cannot encode a multi-view EXR: " + std::to_string(viewNames.size()) + " names for " +
                  std::to_string(frame.views) + " views (a caller bug)");
  }
  const std::size_t views = frame.views;
  std::vector<std::string> channels;
  for (const std::string& name : viewNames) {
    for (const char* c : {"R", "G", "B", "A"}) channels.push_back(name + "." + c);
  }
  // Channel-interleaved pixels: for each pixel, view 0 RGBA, view 1 RGBA, ...
  std::vector<float> pixels(frame.rgba.size());
  const std::size_t pixelCount = std::size_t(frame.width) * frame.height;
  for (std::size_t v = 0; v < views; ++v) {
    const float* view = frame.view(std::uint32_t(v)).rgba.data();
    for (std::size_t i = 0; i < pixelCount; ++i) {
      for (int c = 0; c < kChannels; ++c) pixels[(i * views + v) * kChannels + c] = view[i * kChannels + c];
    }
  }
  return encodeChannels(frame.width, frame.height, channels, pixels, format, attributes, &viewNames);
}

}  // namespace ht::frame_io
