// quilt_file.h - a quilt image file (vendor or holotrace) made into the native image of a lenticular panel: its tile
// layout found from the caller's values, the file name's `_qs` tag or the metadata holotrace embeds, checked against
// the display (camera_models/quilt_interleave.h checkQuiltFitsDisplay) and interleaved with a view filter
// (interleaveQuilt). Used by `holotrace interleave` and by the daemon's quilt content (docs/OPTICS.md §4.4).
//
// Layout, each value from the first source that has it:
//   columns, rows   the caller's hints (both or neither), the name's last `_qs{c}x{r}` tag, the embedded metadata
//   render aspect   the caller's hint, the name's long tag `_qs{c}x{r}a{aspect}`, the metadata, else (short tag
//                   `_qs8x13`, as Looking Glass Bridge accepts it) the display's own screenW/screenH
// When the name's tag and the metadata both give columns and rows they must agree (a renamed file is refused rather
// than guessed at). Tile sizes come from the image size (quilt_layout.h makeQuiltLayout).
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "camera_models/display_config.h"
#include "camera_models/quilt_interleave.h"
#include "camera_models/quilt_layout.h"
#include "frame_io/image_reading.h"

namespace ht::frame_io {

struct QuiltLayoutHints {
  std::optional<std::uint32_t> columns, rows;
  std::optional<double> aspect;
};

struct QuiltFileLayout {
  QuiltLayout layout;
  std::string source;  // where columns and rows came from: "options", "file name" or "metadata"
};

// The layout of the quilt image `header` (one view) of file `fileName` for `display`. Throws UsageError when only
// one of hints.columns / hints.rows is set; ConfigError naming the file and field when no source gives columns and
// rows, the name's tag is malformed, the name and the metadata disagree, or the image has more than one view.
QuiltFileLayout resolveQuiltLayout(const ImageHeader& header, const std::string& fileName,
                                   const QuiltLayoutHints& hints, const DisplayConfig& display);

// A panel image: screenW x screenH linear RGBA, row 0 = top (the layout of a direct lenticular render).
struct InterleavedQuilt {
  QuiltFileLayout layout;
  std::uint32_t width = 0, height = 0;
  std::vector<float> rgba;
};

// Reads the quilt file, resolves its layout, checks that it fits the display (before reading any pixels) and
// interleaves it with `filter` on `threads` threads. Throws IoError (the file) or ConfigError (layout, fit).
InterleavedQuilt interleaveQuiltFile(const std::filesystem::path& path, const DisplayConfig& display,
                                     const QuiltLayoutHints& hints, QuiltViewFilter filter, unsigned threads);

// The same for a quilt already decoded (`image`, named `fileName`): the one path from quilt pixels to a panel image
// that `holotrace interleave`, `holotrace show` and the daemon's quilt content share.
InterleavedQuilt interleaveQuiltImage(const ImageFile& image, const std::string& fileName, const DisplayConfig& display,
                                      const QuiltLayoutHints& hints, QuiltViewFilter filter, unsigned threads);

// Columns and rows of a quilt from what travels with the file alone (its name's tag or the embedded metadata; no
// hints, no display), with the checks that need no display: name and metadata agree, 2 to kMaxQuiltViews views, tiles
// of at least 2x2 pixels. What the daemon checks when a quilt arrives. Throws ConfigError naming the file and field.
QuiltLayout quiltLayoutOfFile(const ImageHeader& header, const std::string& fileName);

// True if `spec` names an image file (.png or .exr, any case) that holotrace shows as a quilt where a scene is asked
// for (`holotrace show --scene`, the daemon's LoadScene and UploadScene).
bool isQuiltImageFile(const std::string& spec);

}  // namespace ht::frame_io
