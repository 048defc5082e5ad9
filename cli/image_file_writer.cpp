// image_file_writer.cpp - see image_file_writer.h.
#include "cli/image_file_writer.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <fstream>

#include <string>
#include <vector>

#include "cli/atomic_output_file.h"
#include "cli/srgb.h"
#include "common/error.h"

namespace ht::cli {
namespace fs = std::filesystem;
namespace {

constexpr int kChannels = 4;

void checkImage(const fs::path& path, const RgbaImageView& image) {
  const std::size_t expected = std::size_t(image.width) * image.height * kChannels;
  if (image.width == 0 || image.height == 0 || image.rgba.size() != expected) {
    throw IoError("cannot write '" + path.string() + "': image is " + std::to_string(image.width) + "x" +
                  std::to_string(image.height) + " with " + std::to_string(image.rgba.size()) +
                  " floats, expected a non-empty image with width*height*4 floats (a renderer bug)");
  }
}

std::vector<std::uint8_t> encodePng8(const RgbaImageView& image) {
  std::vector<std::uint8_t> bytes(image.rgba.size());
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    const bool isAlpha = i % kChannels == 3;
    bytes[i] = isAlpha ? linearEncode8(image.rgba[i]) : srgbEncode8(image.rgba[i]);
  }
  return bytes;
}

OIIO::ImageSpec makeSpec(const RgbaImageView& image, ImageFormat format) {
  const OIIO::TypeDesc type = format == ImageFormat::Png8Srgb  ? OIIO::TypeDesc::UINT8
                              : format == ImageFormat::ExrHalf ? OIIO::TypeDesc::HALF
                                                               : OIIO::TypeDesc::FLOAT;
  OIIO::ImageSpec spec(int(image.width), int(image.height), kChannels, type);
  spec.attribute("oiio:ColorSpace", format == ImageFormat::Png8Srgb ? "sRGB" : "Linear");
  spec.attribute("Software", "holotrace");
  // Store the colour values exactly as given: without this OIIO would treat them as premultiplied and divide
  // by alpha before writing the (unassociated-alpha) PNG.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (format != ImageFormat::Png8Srgb) spec.attribute("compression", "zip");
  return spec;
}

[[noreturn]] void throwOiio(const fs::path& path, const std::string& step, std::string detail) {
  if (detail.empty()) detail = OIIO::geterror();
  if (detail.empty()) detail = "unknown OpenImageIO error";
  throw IoError("cannot write '" + path.string() + "': " + step + ": " + detail);
}

// Writes pixels (already in the spec's type, or float for EXR) to `file`, which must not exist yet.
void writeWithOiio(const fs::path& target, const fs::path& file, const OIIO::ImageSpec& spec, OIIO::TypeDesc dataType,
                   const void* pixels, const char* formatName) {
  auto out = OIIO::ImageOutput::create(formatName);
  if (!out) throwOiio(target, std::string("no OpenImageIO writer for ") + formatName, "");
  if (!out->open(file.string(), spec)) throwOiio(target, "open", out->geterror());
  if (!out->write_image(dataType, pixels)) {
    std::string error = out->geterror();
    out->close();
    throwOiio(target, "write", error);
  }
  if (!out->close()) throwOiio(target, "close", out->geterror());
}

}  // namespace

void writeImageFile(const fs::path& path, const RgbaImageView& image, ImageFormat format,
                    const ImageAttributes& attributes) {
  checkImage(path, image);
  AtomicOutputFile file(path);
  OIIO::ImageSpec spec = makeSpec(image, format);
  for (const auto& [name, value] : attributes) spec.attribute(name, value);
  if (format == ImageFormat::Png8Srgb) {
    const std::vector<std::uint8_t> bytes = encodePng8(image);
    writeWithOiio(path, file.tempPath(), spec, OIIO::TypeDesc::UINT8, bytes.data(), "png");
  } else {
    writeWithOiio(path, file.tempPath(), spec, OIIO::TypeDesc::FLOAT, image.rgba.data(), "openexr");
  }
  file.commit();
}

std::vector<std::uint8_t> encodeMultiViewExr(std::uint32_t width, std::uint32_t height, std::span<const float> rgba,
                                             const std::vector<std::string>& viewNames, ImageFormat format,
                                             const ImageAttributes& attributes) {
  const std::size_t views = viewNames.size();
  const std::size_t viewFloats = std::size_t(width) * height * kChannels;
  if (views == 0 || width == 0 || height == 0 || rgba.size() != viewFloats * views || format == ImageFormat::Png8Srgb) {
    throw IoError("cannot encode a multi-view EXR: " + std::to_string(views) + " views of " + std::to_string(width) +
                  "x" + std::to_string(height) + " with " + std::to_string(rgba.size()) + " floats as " +
                  (format == ImageFormat::Png8Srgb ? "PNG" : "EXR") +
                  ", expected EXR and views*width*height*4 floats (a renderer bug)");
  }
  const OIIO::TypeDesc type = format == ImageFormat::ExrHalf ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
  OIIO::ImageSpec spec(int(width), int(height), int(views * kChannels), type);
  spec.channelnames.clear();
  for (const std::string& name : viewNames) {
    for (const char* c : {"R", "G", "B", "A"}) spec.channelnames.push_back(name + "." + c);
  }
  spec.alpha_channel = -1;  // several alpha channels; none is "the" alpha
  std::vector<const char*> names;
  for (const std::string& name : viewNames) names.push_back(name.c_str());
  spec.attribute("multiView", OIIO::TypeDesc(OIIO::TypeDesc::STRING, int(views)), names.data());
  spec.attribute("oiio:ColorSpace", "Linear");
  spec.attribute("Software", "holotrace");
  spec.attribute("compression", "zip");
  for (const auto& [name, value] : attributes) spec.attribute(name, value);
  // Channel-interleaved pixels: for each pixel, view 0 RGBA, view 1 RGBA, ...
  std::vector<float> pixels(rgba.size());
  const std::size_t pixelCount = std::size_t(width) * height;
  for (std::size_t v = 0; v < views; ++v) {
    for (std::size_t i = 0; i < pixelCount; ++i) {
      for (int c = 0; c < kChannels; ++c) pixels[(i * views + v) * kChannels + c] = rgba[v * viewFloats + i * kChannels + c];
    }
  }
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto out = OIIO::ImageOutput::create("openexr");
  if (!out || !out->set_ioproxy(&proxy) || !out->open("views.exr", spec) ||
      !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !out->close()) {
    std::string detail = out ? out->geterror() : OIIO::geterror();
    throw IoError("cannot encode a multi-view EXR: " + (detail.empty() ? std::string("unknown OpenImageIO error") : detail));
  }
  return {bytes.begin(), bytes.end()};
}

void writeMultiViewExr(const fs::path& path, std::uint32_t width, std::uint32_t height, std::span<const float> rgba,
                       const std::vector<std::string>& viewNames, ImageFormat format, const ImageAttributes& attributes) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = encodeMultiViewExr(width, height, rgba, viewNames, format, attributes);
  } catch (const IoError& e) {
    throw IoError("cannot write '" + path.string() + "': " + e.what());
  }
  AtomicOutputFile file(path);
  {
    std::ofstream stream(file.tempPath(), std::ios::binary);
    stream.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    stream.flush();
    if (!stream) throw IoError("cannot write '" + path.string() + "': write failed (disk full?)");
  }
  file.commit();
}

}  // namespace ht::cli
