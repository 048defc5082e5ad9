// view_mosaic.cpp - see view_mosaic.h.
#include "frame_io/view_mosaic.h"

#include <algorithm>
#include <string>

#include "common/error.h"

namespace ht::frame_io {

RgbaImage assembleQuilt(const FrameImages& frame, const QuiltLayout& layout) {
  checkFrame(frame, "cannot assemble a quilt");
  if (frame.views != layout.views() || frame.width != layout.tileWidth || frame.height != layout.tileHeight) {
    throw IoError("quilt layout " + std::to_string(layout.columns) + "x" + std::to_string(layout.rows) + " of " +
                  std::to_string(layout.tileWidth) + "x" + std::to_string(layout.tileHeight) +
                  " tiles does not match " + std::to_string(frame.views) + " views of " + std::to_string(frame.width) +
                  "x" + std::to_string(frame.height) + " (a renderer bug)");
  }
  RgbaImage quilt{layout.quiltWidth, layout.quiltHeight,
                  std::vector<float>(std::size_t(layout.quiltWidth) * layout.quiltHeight * 4, 0.0f)};
  for (std::size_t i = 3; i < quilt.rgba.size(); i += 4) quilt.rgba[i] = 1.0f;
  for (std::uint32_t v = 0; v < frame.views; ++v) {
    const glm::uvec2 origin = quiltTileOrigin(layout, v);  // lower-left, y from the bottom
    const RgbaImageView view = frame.view(v);
    for (std::uint32_t row = 0; row < frame.height; ++row) {  // row from the top of the view
      const std::uint32_t quiltRowFromBottom = origin.y + (frame.height - 1 - row);
      const std::uint32_t quiltRow = layout.quiltHeight - 1 - quiltRowFromBottom;
      const float* src = view.rgba.data() + std::size_t(row) * frame.width * 4;
      float* dst = quilt.rgba.data() + (std::size_t(quiltRow) * layout.quiltWidth + origin.x) * 4;
      std::copy(src, src + std::size_t(frame.width) * 4, dst);
    }
  }
  return quilt;
}

RgbaImage mosaicImage(const FrameImages& frame, const std::optional<QuiltLayout>& quilt) {
  if (frame.views > 1 && quilt) return assembleQuilt(frame, *quilt);
  checkFrame(frame, "cannot stack the views");
  // View-major rows are already view 0 on top.
  return {frame.width, frame.height * frame.views, std::vector<float>(frame.rgba.begin(), frame.rgba.end())};
}

}  // namespace ht::frame_io
