// frame_outputs.h - writes a rendered frame in the form its display needs: one image (native panel, LCD, pinhole),
// a quilt (quilt cameras, capture grids: standard `_qs{cols}x{rows}a{aspect}` name plus JSON metadata, embedded and
// as a sidecar), a per-view PNG sequence (projector images, or any multi-view frame on request), and an OpenEXR file
// with the multiView attribute for every multi-view frame.
#pragma once
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include "camera_models/display_config.h"
#include "cli/output_paths.h"
#include "cli/view_layout.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu/view_mosaic.h"

namespace ht::cli {

// The quilt file name: `path` unchanged if it already carries a `_qs` tag, else the tag is appended to its stem.
std::filesystem::path quiltFilePath(const std::filesystem::path& path, const QuiltLayout& layout);

void writeFrameOutputs(std::ostream& out, const OutputPaths& paths, const gpu::RenderResult& frame,
                       const DisplayConfig& display, const gpu::DisplayCamera& camera, ViewLayout layout);

}  // namespace ht::cli
