// image_file_writer.cpp - see image_file_writer.h.
#include "cli/image_file_writer.h"

#include <OpenImageIO/imageio.h>

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

void writeImageFile(const fs::path& path, const RgbaImageView& image, ImageFormat format) {
  checkImage(path, image);
  AtomicOutputFile file(path);
  const OIIO::ImageSpec spec = makeSpec(image, format);
  if (format == ImageFormat::Png8Srgb) {
    const std::vector<std::uint8_t> bytes = encodePng8(image);
    writeWithOiio(path, file.tempPath(), spec, OIIO::TypeDesc::UINT8, bytes.data(), "png");
  } else {
    writeWithOiio(path, file.tempPath(), spec, OIIO::TypeDesc::FLOAT, image.rgba.data(), "openexr");
  }
  file.commit();
}

}  // namespace ht::cli
