// quilt_layout.h - Looking Glass quilts: the `_qs{cols}x{rows}a{aspect}` file-name tag, tile layout and the device
// default quilt sizes (docs/OPTICS.md §4.1, §4.2). Host side only; the quilt cameras are quilt_model.h.
//
// Layout (holoplaycore.js GetQuiltCoordinates; LKG-Toolkit QuiltSettings.ViewPortion*, docs/OPTICS.md §4.1): view i
// sits in tile (i mod cols, floor(i / cols)) counted from the BOTTOM-LEFT in GL texture space (y up); view 0 is the
// leftmost camera, views run left to right, then upward. Tiles are tileW x tileH pixels; the quilt may be larger than
// cols*tileW x rows*tileH (the unused remainder is the "view portion" < 1).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "camera_models/display_config.h"

namespace ht {

// What a quilt file name says: columns, rows and, in the long form, the render aspect (W/H of the camera that rendered
// the views, not the tile aspect: QuiltSettings.cs `renderAspect`).
struct QuiltName {
  std::uint32_t columns = 0, rows = 0;
  std::optional<double> aspect;  // nullopt for the short Bridge form `_qs8x13`
};

// Finds the tag `_qs{cols}x{rows}a{aspect}` (looking-glass-webxr LookingGlassMediaController.ts; parsers match
// `_qs(\d+)x(\d+)a([\d.]+)`) or the short `_qs{cols}x{rows}` (bridge.js README) in a file name or path; the last tag
// wins. Throws ConfigError(name, "quilt name", ...) when there is no tag, a count is 0 or > 1024, or the aspect is not
// a finite number > 0.
QuiltName parseQuiltName(std::string_view fileName);

// True if the name holds a quilt tag at all (`_qs{digits}x{digits}`), well-formed or not: parseQuiltName reads it
// (and names what is wrong with it); a name without one carries no layout.
bool hasQuiltTag(std::string_view fileName);

// "_qs{cols}x{rows}a{aspect}" with the aspect in the shortest form that reads back to the same double.
std::string formatQuiltName(std::uint32_t columns, std::uint32_t rows, double aspect);

struct QuiltLayout {
  std::uint32_t columns = 0, rows = 0;
  std::uint32_t quiltWidth = 0, quiltHeight = 0;  // whole quilt texture (pixels)
  std::uint32_t tileWidth = 0, tileHeight = 0;    // floor(quiltWidth / columns), floor(quiltHeight / rows)
  double aspect = 1.0;                            // render aspect W/H of the view cameras
  std::uint32_t views() const { return columns * rows; }
};

// Tiles of floor(quilt / count) pixels. Throws ConfigError when a count or size is 0 or a tile would be empty.
QuiltLayout makeQuiltLayout(std::uint32_t columns, std::uint32_t rows, std::uint32_t quiltWidth,
                            std::uint32_t quiltHeight, double aspect);

// The config's camera.quilt when it has one, else the device default quilt (docs/OPTICS.md §4.2, LKG-Toolkit
// templates / webxr quiltResolution), chosen by panel size and
// generation (CellPatternMode != 0 = Gen3): Portrait 1536x2048 -> 3360^2 8x6; Go 1440x2560 -> 4092^2 11x6;
// Gen3 16" 3840x2160 -> 6000^2 7x7, 2160x3840 -> 6000^2 11x6; Gen3 32" 7680x4320 -> 8190^2 7x7, 4320x7680 -> 8184^2
// 11x6; Gen2 32" 7680x4320 -> 8192^2 5x9; other (8.9"/15.6"/16" Gen2) -> 4096^2 5x9. Aspect = screenW/screenH.
// Throws ConfigError if the config is not a lenticular display.
QuiltLayout defaultQuiltLayout(const DisplayConfig& config);

// Lower-left pixel of view i's tile in the quilt (y from the bottom).
glm::uvec2 quiltTileOrigin(const QuiltLayout& layout, std::uint32_t view);

// Quilt texture uv (v from the bottom) of tile uv `tileUV` in view i (holoplaycore.js GetQuiltCoordinates with the
// view portions of QuiltSettings: quilt_uv = ((tileX + tile_uv.x)/cols*portionX, (tileY + tile_uv.y)/rows*portionY)).
glm::dvec2 quiltUV(const QuiltLayout& layout, std::uint32_t view, glm::dvec2 tileUV);

// Which view and tile pixel a quilt pixel (y from the bottom) belongs to; nullopt in the unused remainder.
struct QuiltTilePixel {
  std::uint32_t view = 0;
  glm::uvec2 pixel{0};
};
std::optional<QuiltTilePixel> quiltTilePixel(const QuiltLayout& layout, glm::uvec2 quiltPixel);

}  // namespace ht
