// frame_file_names.h - the names of the files of a frame, derived from the one name asked for ("shot.png"):
//   per-view files   shot_v00.png, shot_v01.png, ... (at least two digits, as many as the last view needs)
//   quilts           shot_qs{columns}x{rows}a{aspect}.png (Looking Glass quilt tag, camera_models/quilt_layout.h)
//                    + shot_qs{columns}x{rows}a{aspect}.json (metadata sidecar)
//   multiView EXR    views named view00, view01, ... (every display model alike)
// Suffixes go before the extension, which is kept as given.
#pragma once
#include <cstdint>
#include <string>

#include "camera_models/quilt_layout.h"

namespace ht::frame_io {

// "07" of 10 views, "007" of 101: zero-padded to max(2, digits of views - 1).
std::string viewNumber(std::uint32_t view, std::uint32_t views);

// The name of view `view` in a multiView EXR: "view" + viewNumber.
std::string multiViewName(std::uint32_t view, std::uint32_t views);

// The stem of frame `index` of a capture sequence `name` (the daemon's Capture, `holotrace capture`): "turn" + 7 ->
// "turn_f0007" (at least four digits).
std::string captureFrameStem(const std::string& name, std::uint32_t index);

// "shot.png" + "_v00" -> "shot_v00.png".
std::string withSuffix(const std::string& fileName, const std::string& suffix);

// "shot.png" + ".json" -> "shot.json".
std::string withExtension(const std::string& fileName, const std::string& extension);

// `fileName` unchanged if its (last) quilt tag already states this layout (columns, rows and aspect), else with the
// layout's tag appended to its stem: a name that states another layout gets the right tag after it, which is the one
// quilt readers take (the last tag wins).
std::string quiltFileName(const std::string& fileName, const QuiltLayout& layout);

}  // namespace ht::frame_io
