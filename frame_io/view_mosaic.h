// view_mosaic.h - the views of a multi-view frame as one image: the quilt when the views form one (view 0 in the
// bottom-left tile, camera_models/quilt_layout.h), else the views stacked top to bottom (view 0 on top).
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "camera_models/quilt_layout.h"
#include "frame_io/frame_images.h"

namespace ht::frame_io {

// One image that owns its pixels (width x height RGBA floats, row 0 = top).
struct RgbaImage {
  std::uint32_t width = 0, height = 0;
  std::vector<float> rgba;
  RgbaImageView view() const { return {width, height, rgba}; }
};

// Tiles the frame's views into the quilt image (row 0 = top; view 0 in the bottom-left tile); the unused remainder of
// the quilt is opaque black. Throws IoError if the layout does not match the frame.
RgbaImage assembleQuilt(const FrameImages& frame, const QuiltLayout& layout);

// The quilt when `quilt` is given, else the views stacked top to bottom (view 0 on top; a one-view frame is itself).
RgbaImage mosaicImage(const FrameImages& frame, const std::optional<QuiltLayout>& quilt);

}  // namespace ht::frame_io
