// quilt_metadata.h - the JSON that travels with a quilt, as a `.json` sidecar and embedded in the quilt PNG's
// ImageDescription: layout (columns, rows, tile and quilt sizes, render aspect, view order), display name and model,
// and for a lenticular display's quilt cameras the view cone, the vertical field of view and the device calibration
// verbatim (the calibration is what interleaving the quilt for that panel needs).
#pragma once
#include <optional>
#include <string>

#include "camera_models/display_config.h"
#include "camera_models/quilt_layout.h"

namespace ht::frame_io {

// Pretty-printed (2-space indent) JSON, no trailing newline. A lenticular display's quilt is rendered by its quilt
// cameras (camera_models/quilt_setup.h): viewConeDeg is their cone as the renderer uses it (float precision).
std::string quiltMetadataJson(const DisplayConfig& display, const QuiltLayout& layout);

// The layout (columns, rows, render aspect) that quiltMetadataJson wrote, read back from a quilt's ImageDescription.
// nullopt when `description` is not holotrace quilt metadata (empty, not JSON, or no "generator": "holotrace": a
// vendor quilt's own description). Throws ConfigError naming `fileName` and the field when it is holotrace metadata
// whose columns, rows or aspect are missing or out of range.
std::optional<QuiltName> readQuiltMetadataLayout(const std::string& description, const std::string& fileName);

}  // namespace ht::frame_io
