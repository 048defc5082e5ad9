// frame_reading.h - a rendered multi-view frame read back from the files `holotrace render` writes (frame_package.h),
// for `holotrace simulate`: one image; a multiView EXR; the per-view PNGs shot_v00.png, shot_v01.png, ... given by
// the first one; or the views stacked top to bottom in one image (the daemon's RenderFrame PNG mosaic).
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

#include "frame_io/frame_images.h"

namespace ht::frame_io {

struct ReadFrame {
  std::uint32_t width = 0, height = 0, views = 1;  // of one view
  std::vector<float> rgba;                         // linear RGBA, view after view, row 0 = top

  FrameImages frame() const { return {width, height, views, rgba}; }
};

// Reads `views` images of width x height from `path` in any of the forms above. Throws IoError naming the file and
// what it holds against what is expected (and which forms are accepted).
ReadFrame readFrameViews(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                         std::uint32_t views);

}  // namespace ht::frame_io
