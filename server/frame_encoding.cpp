// frame_encoding.cpp - see frame_encoding.h. PNG/EXR are encoded into memory through an OpenImageIO IOProxy
// (ImageOutput::set_ioproxy + Filesystem::IOVecOutput, OpenImageIO imageio.h / filesystem.h), so the
// FileSink alone decides where bytes land.
#include "server/frame_encoding.h"

#include <Imath/half.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <cstring>

#include "cli/srgb.h"
#include "common/error.h"

namespace ht::server {
namespace {

std::vector<std::uint8_t> toRgba8(const gpu::RenderResult& f) {
  std::vector<std::uint8_t> out(f.rgba.size());
  for (std::size_t i = 0; i < f.rgba.size(); ++i) {
    out[i] = (i % 4 == 3) ? cli::linearEncode8(f.rgba[i]) : cli::srgbEncode8(f.rgba[i]);
  }
  return out;
}

std::vector<std::uint8_t> toRgba16f(const gpu::RenderResult& f) {
  std::vector<std::uint8_t> out(f.rgba.size() * 2);
  for (std::size_t i = 0; i < f.rgba.size(); ++i) {
    const std::uint16_t bits = Imath::half(f.rgba[i]).bits();
    std::memcpy(out.data() + 2 * i, &bits, 2);  // little endian host (x86-64 / aarch64)
  }
  return out;
}

std::vector<std::uint8_t> encodeFile(const gpu::RenderResult& f, const char* extension, bool png) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto output = OIIO::ImageOutput::create(extension);
  if (!output) throw IoError(std::string("OpenImageIO has no ") + extension + " writer");
  OIIO::ImageSpec spec(static_cast<int>(f.width), static_cast<int>(f.height), 4,
                       png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::HALF);
  if (png) spec.attribute("oiio:ColorSpace", "sRGB");
  if (!output->set_ioproxy(&proxy)) throw IoError(std::string("OpenImageIO cannot write ") + extension + " to memory");
  if (!output->open(std::string("frame.") + extension, spec)) throw IoError("encode: " + output->geterror());
  bool ok = false;
  if (png) {
    const std::vector<std::uint8_t> pixels = toRgba8(f);
    ok = output->write_image(OIIO::TypeDesc::UINT8, pixels.data());
  } else {
    ok = output->write_image(OIIO::TypeDesc::FLOAT, f.rgba.data());
  }
  if (!ok || !output->close()) throw IoError("encode: " + output->geterror());
  return {bytes.begin(), bytes.end()};
}

}  // namespace

std::vector<std::uint8_t> encodeFrame(const gpu::RenderResult& frame, FrameEncoding encoding) {
  switch (encoding) {
    case FrameEncoding::Rgba8Srgb: return toRgba8(frame);
    case FrameEncoding::Rgba16fLinear: return toRgba16f(frame);
    case FrameEncoding::Png8Srgb: return encodeFile(frame, "png", true);
    case FrameEncoding::ExrHalf: return encodeFile(frame, "exr", false);
  }
  return {};
}

}  // namespace ht::server
