// frame_encoding.h - a rendered frame (linear float RGBA, row 0 = top) as bytes for the wire or a file.
#pragma once
#include <cstdint>
#include <vector>

#include "gpu/renderer.h"

namespace ht::server {

enum class FrameEncoding { Rgba8Srgb, Rgba16fLinear, Png8Srgb, ExrHalf };

// Throws IoError if OpenImageIO fails to encode PNG/EXR.
std::vector<std::uint8_t> encodeFrame(const gpu::RenderResult& frame, FrameEncoding encoding);

}  // namespace ht::server
