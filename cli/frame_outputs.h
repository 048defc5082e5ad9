// frame_outputs.h - `holotrace render`'s output files: the frame packaged by frame_io (frame_io/frame_package.h: one
// image, a quilt + its metadata, one PNG per view, a multiView EXR) and written atomically, every file of the frame as
// one set (frame_io/atomic_output_file.h).
#pragma once
#include <ostream>

#include "camera_models/display_config.h"
#include "cli/output_paths.h"
#include "frame_io/frame_package.h"
#include "gpu/renderer.h"

namespace ht::cli {

// Throws UsageError ("holotrace render: --layout quilt: ...") when the layout cannot be written for this display, so
// the command can refuse it before rendering.
void checkViewLayout(const frame_io::FrameDisplay& display, std::uint32_t views, frame_io::ViewLayout layout);

// Packages the frame for -o (PNG) and --exr (EXR), writes all files, then prints one line per format.
void writeFrameOutputs(std::ostream& out, const OutputPaths& paths, const gpu::RenderResult& frame,
                       const frame_io::FrameDisplay& display, frame_io::ViewLayout layout);

}  // namespace ht::cli
