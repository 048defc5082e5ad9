// frame_images.h - the pixels of a rendered frame as frame_io takes them: `views` images of width x height, linear
// float RGBA, view after view, row 0 = each view's top. Views of the caller's memory (gpu::RenderResult::rgba, a
// decoded file), never copies, so frame_io does not depend on the renderer.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>

namespace ht::frame_io {

// One image: width x height RGBA floats, row 0 = top.
struct RgbaImageView {
  std::uint32_t width = 0, height = 0;
  std::span<const float> rgba;  // width * height * 4 floats
};

struct FrameImages {
  std::uint32_t width = 0, height = 0;  // of one view
  std::uint32_t views = 1;
  std::span<const float> rgba;  // views * width * height * 4 floats

  std::size_t viewFloats() const { return std::size_t(width) * height * 4; }
  RgbaImageView view(std::uint32_t v) const { return {width, height, rgba.subspan(v * viewFloats(), viewFloats())}; }
};

// Throws IoError naming `what` unless the image is non-empty and holds exactly width * height * 4 floats.
void checkImage(const RgbaImageView& image, const char* what);
// Throws IoError naming `what` unless the frame is non-empty and holds exactly views * width * height * 4 floats.
void checkFrame(const FrameImages& frame, const char* what);

}  // namespace ht::frame_io
