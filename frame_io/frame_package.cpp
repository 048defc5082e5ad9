// frame_package.cpp - see frame_package.h.
#include "frame_io/frame_package.h"

#include "common/error.h"
#include "frame_io/frame_file_names.h"
#include "frame_io/image_encoding.h"
#include "frame_io/quilt_metadata.h"
#include "frame_io/view_mosaic.h"

namespace ht::frame_io {
namespace {

std::string size(std::uint32_t width, std::uint32_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

FramePackage single(const FrameImages& frame, FrameFormat format, const std::string& fileName) {
  const bool png = format == FrameFormat::Png;
  return {{{fileName, encodeImage(frame.view(0), png ? ImageFormat::Png8Srgb : ImageFormat::ExrHalf)}},
          size(frame.width, frame.height) + (png ? ", 8-bit sRGB PNG" : ", linear half EXR")};
}

FramePackage multiViewExr(const FrameImages& frame, const std::string& fileName) {
  std::vector<std::string> names;
  for (std::uint32_t v = 0; v < frame.views; ++v) names.push_back(multiViewName(v, frame.views));
  return {
      {{fileName, encodeMultiViewExr(frame, names, ImageFormat::ExrHalf)}},
      std::to_string(frame.views) + " views of " + size(frame.width, frame.height) + ", linear half EXR, multiView"};
}

// The quilt PNG with its metadata embedded, and the metadata again as a sidecar.
FramePackage quilt(const FrameImages& frame, const FrameDisplay& display, const std::string& fileName) {
  const QuiltLayout& layout = *display.quilt;
  const std::string name = quiltFileName(fileName, layout);
  const std::string metadata = quiltMetadataJson(display.config, layout);
  const RgbaImage image = assembleQuilt(frame, layout);
  std::vector<std::uint8_t> sidecar(metadata.begin(), metadata.end());
  sidecar.push_back('\n');
  return {{{name, encodeImage(image.view(), ImageFormat::Png8Srgb, {{"ImageDescription", metadata}})},
           {withExtension(name, ".json"), std::move(sidecar)}},
          "quilt " + size(layout.columns, layout.rows) + " of " + size(layout.tileWidth, layout.tileHeight) +
              " tiles, " + size(layout.quiltWidth, layout.quiltHeight) + ", 8-bit sRGB PNG with JSON metadata"};
}

FramePackage viewSequence(const FrameImages& frame, const std::string& fileName) {
  FramePackage package;
  for (std::uint32_t v = 0; v < frame.views; ++v) {
    package.files.push_back(
        {withSuffix(fileName, "_v" + viewNumber(v, frame.views)), encodeImage(frame.view(v), ImageFormat::Png8Srgb)});
  }
  package.description =
      std::to_string(frame.views) + " views of " + size(frame.width, frame.height) + ", 8-bit sRGB PNG each";
  return package;
}

}  // namespace

bool layoutAllowed(const FrameDisplay& display, std::uint32_t views, ViewLayout layout) {
  return views == 1 || layout != ViewLayout::Quilt || display.quilt.has_value();
}

FramePackage packageFrame(const FrameImages& frame, const FrameDisplay& display, ViewLayout layout, FrameFormat format,
                          const std::string& fileName) {
  checkFrame(frame, ("cannot write '" + fileName + "'").c_str());
  if (!layoutAllowed(display, frame.views, layout)) {
    throw UsageError("layout quilt: the " + std::to_string(frame.views) + " views of a '" +
                     std::string(displayModelName(display.config.model)) +
                     "' display do not form a quilt; write them as views");
  }
  if (frame.views == 1) return single(frame, format, fileName);
  if (format == FrameFormat::Exr) return multiViewExr(frame, fileName);
  if (display.quilt && layout != ViewLayout::Views) return quilt(frame, display, fileName);
  return viewSequence(frame, fileName);
}

MosaicPng encodeMosaicPng(const FrameImages& frame, const FrameDisplay& display) {
  checkFrame(frame, "cannot encode the frame as PNG");
  if (frame.views == 1) return {frame.width, frame.height, encodeImage(frame.view(0), ImageFormat::Png8Srgb)};
  if (display.quilt) {
    FramePackage package = quilt(frame, display, "frame.png");
    return {display.quilt->quiltWidth, display.quilt->quiltHeight, std::move(package.files.front().bytes)};
  }
  const RgbaImage stacked = mosaicImage(frame, std::nullopt);
  return {stacked.width, stacked.height, encodeImage(stacked.view(), ImageFormat::Png8Srgb)};
}

}  // namespace ht::frame_io
