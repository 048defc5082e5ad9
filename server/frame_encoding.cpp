// frame_encoding.cpp - see frame_encoding.h.
#include "server/frame_encoding.h"

#include "frame_io/pixel_encoding.h"

namespace ht::server {

void encodeFrame(const gpu::RenderResult& frame, FrameEncoding encoding, const frame_io::FrameDisplay& display,
                 EncodedFrame& into) {
  into.width = frame.width;
  into.height = frame.height;
  into.views = frame.views;
  switch (encoding) {
    case FrameEncoding::Rgba8Srgb:
      into.bytes.resize(frame.rgba.size());
      frame_io::encodeRgba8Srgb(frame.rgba, into.bytes);
      return;
    case FrameEncoding::Rgba16fLinear:
      into.bytes.resize(2 * frame.rgba.size());
      frame_io::encodeRgba16fLinear(frame.rgba, into.bytes);
      return;
    case FrameEncoding::Png8Srgb: break;
  }
  frame_io::MosaicPng png = frame_io::encodeMosaicPng({frame.width, frame.height, frame.views, frame.rgba}, display);
  into = {png.width, png.height, 1, std::move(png.bytes)};
}

EncodedFrame encodeFrame(const gpu::RenderResult& frame, FrameEncoding encoding,
                         const frame_io::FrameDisplay& display) {
  EncodedFrame encoded;
  encodeFrame(frame, encoding, display, encoded);
  return encoded;
}

}  // namespace ht::server
