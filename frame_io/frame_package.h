// frame_package.h - a rendered frame as the files that hold it, one rule for every writer: `holotrace render` (writes
// them atomically to paths), the daemon's Capture (writes them through its confined FileSink), its RenderFrame /
// StreamFrames PNG (the mosaic image's bytes) and a display sink (the 8-bit panel image, pixel_encoding.h).
//
// For FrameFormat::Png and requested name "shot.png":
//   one view                  shot.png                                   8-bit sRGB
//   views forming a quilt     shot_qs{c}x{r}a{aspect}.png + .json        (layout Auto or Quilt) the quilt, its metadata
//                                                                        embedded as ImageDescription and as sidecar
//   other views, or Views     shot_v00.png, shot_v01.png, ...            one 8-bit sRGB image per view
// For FrameFormat::Exr and "shot.exr": shot.exr, linear half float; a multi-view frame as one multiView EXR with views
// view00, view01, ... (every model alike). Layout Quilt for views that do not form a quilt is refused (UsageError)
// whatever the format; callers check it with layoutAllowed() before rendering. A one-view frame ignores the layout.
//
// Files come in the order they should appear (a quilt before its sidecar); writers commit them as a set, so a frame
// is on disk whole or not at all (frame_io/atomic_output_file.h, the daemon's FileSink::writeFiles).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "camera_models/display_config.h"
#include "camera_models/quilt_layout.h"
#include "frame_io/frame_images.h"
#include "frame_io/view_layout.h"

namespace ht::frame_io {

enum class FrameFormat {
  Png,  // 8-bit sRGB
  Exr,  // linear half float
};

// What packaging needs to know about the display a frame was rendered for.
struct FrameDisplay {
  const DisplayConfig& config;       // name, model, calibration (quilt metadata)
  std::optional<QuiltLayout> quilt;  // the tile layout when the views form a quilt (gpu::DisplayCamera::quilt)
};

struct FrameFile {
  std::string name;  // one file name, no directory
  std::vector<std::uint8_t> bytes;
};

struct FramePackage {
  std::vector<FrameFile> files;
  std::string description;  // for messages: "quilt 3x2 of 24x16 tiles, 72x32, 8-bit sRGB PNG"
};

// False only for layout Quilt of a multi-view frame whose views do not form a quilt.
bool layoutAllowed(const FrameDisplay& display, std::uint32_t views, ViewLayout layout);

// The files of `frame` in `format`, named from `fileName` (e.g. "shot.png"; its extension is kept). Throws UsageError
// for a layout that is not allowed, IoError for a frame whose pixels do not match its size or an encoding failure.
FramePackage packageFrame(const FrameImages& frame, const FrameDisplay& display, ViewLayout layout, FrameFormat format,
                          const std::string& fileName);

// The frame as one 8-bit sRGB PNG: a one-view frame itself, else the quilt (with its metadata embedded, the same
// bytes packageFrame writes) when the views form one, else the views stacked top to bottom (view 0 on top). Throws
// IoError.
struct MosaicPng {
  std::uint32_t width = 0, height = 0;  // of the image in `bytes`
  std::vector<std::uint8_t> bytes;
};
MosaicPng encodeMosaicPng(const FrameImages& frame, const FrameDisplay& display);

}  // namespace ht::frame_io
