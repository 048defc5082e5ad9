// frame_encoding.h - a rendered frame as the bytes of a RenderFrame / StreamFrames message (proto PixelFormat). The
// pixel codes and the PNG come from frame_io (frame_io/pixel_encoding.h, frame_io/frame_package.h), so a streamed PNG
// is byte for byte the file `holotrace render` and Capture write for the same frame.
#pragma once
#include <cstdint>
#include <vector>

#include "frame_io/frame_package.h"
#include "gpu/renderer.h"

namespace ht::server {

enum class FrameEncoding { Rgba8Srgb, Rgba16fLinear, Png8Srgb };

struct EncodedFrame {
  std::uint32_t width = 0, height = 0;  // of each image in `bytes`
  std::uint32_t views = 1;              // images in `bytes`: the frame's views (raw formats), 1 (PNG)
  std::vector<std::uint8_t> bytes;
};

// Raw formats carry every view one after the other; PNG carries one image: the view of a one-view frame, else the
// quilt (metadata embedded) when the views form one, else the views stacked top to bottom. `display` matters for PNG
// only. Throws IoError if encoding fails.
EncodedFrame encodeFrame(const gpu::RenderResult& frame, FrameEncoding encoding, const frame_io::FrameDisplay& display);
// The same into `into`, whose byte buffer is reused: a stream encodes every frame into one buffer instead of a new
// one per frame (a Portrait panel image is 12.6 MB, and fresh pages cost more than the writes into them).
void encodeFrame(const gpu::RenderResult& frame, FrameEncoding encoding, const frame_io::FrameDisplay& display,
                 EncodedFrame& into);

}  // namespace ht::server
