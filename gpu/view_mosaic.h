// view_mosaic.h - the views of a multi-view frame as one image: the quilt (view 0 in the bottom-left tile,
// optics.md §4.1) when the views form one, else stacked top to bottom (view 0 on top); and the quilt's JSON
// metadata. Used by the CLI's outputs and the daemon's frames and captures.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "camera_models/display_config.h"
#include "camera_models/quilt_layout.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"

namespace ht::gpu {

// Tiles the frame's views into the quilt image (row 0 = top; view 0 in the bottom-left tile, optics.md §4.1);
// the unused remainder of the quilt is opaque black. Throws IoError if the layout does not match the frame.
std::vector<float> assembleQuilt(const RenderResult& frame, const QuiltLayout& layout);

// A one-view frame of the same content: the quilt when `quilt` is given, else the views stacked top to bottom
// (view 0 on top). A one-view frame is returned unchanged.
RenderResult singleImage(const RenderResult& frame, const std::optional<QuiltLayout>& quilt);

// JSON metadata of a quilt: layout, view cone, display name, and for a lenticular display its calibration verbatim.
std::string quiltMetadataJson(const DisplayConfig& display, const DisplayCamera& camera);

}  // namespace ht::gpu
