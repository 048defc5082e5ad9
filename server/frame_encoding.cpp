// frame_encoding.cpp - see frame_encoding.h.
#include "server/frame_encoding.h"

#include "frame_io/pixel_encoding.h"

namespace ht::server {

EncodedFrame encodeFrame(const gpu::RenderResult& frame, FrameEncoding encoding,
                         const frame_io::FrameDisplay& display) {
  switch (encoding) {
    case FrameEncoding::Rgba8Srgb:
      return {frame.width, frame.height, frame.views, frame_io::encodeRgba8Srgb(frame.rgba)};
    case FrameEncoding::Rgba16fLinear:
      return {frame.width, frame.height, frame.views, frame_io::encodeRgba16fLinear(frame.rgba)};
    case FrameEncoding::Png8Srgb: break;
  }
  frame_io::MosaicPng png = frame_io::encodeMosaicPng({frame.width, frame.height, frame.views, frame.rgba}, display);
  return {png.width, png.height, 1, std::move(png.bytes)};
}

}  // namespace ht::server
