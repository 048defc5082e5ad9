// quilt_interleave.h - a quilt of views -> the native image of a lenticular panel, on the CPU, as the Looking Glass
// shaders do it (docs/OPTICS.md §3, §4.1; holoplaycore.js `Shader`, HoloPlayCore C `HoloPlayShaders.h`):
// every subpixel (x, y, c) of the panel takes the view phase t of the shared lenticular model at the subpixel's
// sample point (lenticular_view_phase(p, x, y, c, xi = (0.5, 0.5)) of lenticular_model.h: classic and Gen3 cell
// offsets, BGR panels and invView included) and samples the views at the pixel's own uv, the same for the three
// channels (holoplaycore.js GetQuiltCoordinates), mirrored like the direct path when flipImageX/Y. Inside a view the
// sample is bilinear and clamped to the view's own tile (the vendor's GL sampler filters across tile borders and
// bleeds neighbouring views into the edge pixels; clamping avoids that).
//
// View filters (z = t*N for N views; view i's camera sits at t = (i + 0.5)/N, quilt_model.h):
//   Nearest      view floor(z)                                   (holoplaycore.js filterMode 0)
//   VendorLerp   mix(view floor(z), view floor(z)+1, fract(z))   (filterMode 1, looking-glass-webxr's default;
//                HoloPlayCore C `mix(col1, col2, z - floor(z))`); the neighbour is clamped to N-1
//   CentredLerp  the same blend on z - 0.5: between the two views whose cameras bracket t, weighted by the distance
//                to each camera (linear interpolation in camera position). Not the vendor's: VendorLerp shows the
//                half-and-half mix of views i and i+1 to a subpixel whose phase is exactly view i's camera, a
//                half-view shift of every subpixel's direction; CentredLerp reproduces view i there. The quality
//                benchmark measures +0.9 to +1.5 dB over VendorLerp against direct per-subpixel rays
//                (docs/BENCHMARKS.md, "Run time vs error"), so it is the better option.
#pragma once
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "camera_models/camera_params.h"
#include "camera_models/display_config.h"
#include "camera_models/quilt_layout.h"

namespace ht {

enum class QuiltViewFilter { Nearest, VendorLerp, CentredLerp };

// "nearest", "vendor-lerp", "centred-lerp".
std::string_view quiltViewFilterName(QuiltViewFilter filter);
// The inverse of quiltViewFilterName (also "vendor" and "centred"/"centered"). Throws UsageError listing the names.
QuiltViewFilter parseQuiltViewFilter(std::string_view name);

// Where the views lie in one linear RGBA float image (row 0 = top, 4 floats per pixel): view i is the
// tileWidth x tileHeight rectangle whose top-left pixel is tileTopLeft[i].
struct QuiltViews {
  std::uint32_t imageWidth = 0, imageHeight = 0;
  std::uint32_t tileWidth = 0, tileHeight = 0;
  std::vector<glm::uvec2> tileTopLeft;
  std::span<const float> rgba;
  std::uint32_t views() const { return static_cast<std::uint32_t>(tileTopLeft.size()); }
};

// A quilt image of layout.quiltWidth x layout.quiltHeight: view i in tile (i mod cols, floor(i/cols)) counted from
// the bottom-left (quilt_layout.h). Throws Error if rgba does not hold that many pixels.
QuiltViews quiltImageViews(const QuiltLayout& layout, std::span<const float> rgba);

// `views` images of width x height one after the other, view 0 first (RenderResult of a quilt render).
// Throws Error if rgba does not hold that many pixels.
QuiltViews viewStackViews(std::uint32_t width, std::uint32_t height, std::uint32_t views, std::span<const float> rgba);

// Checks that a quilt can be shown on a lenticular display, before any pixel work. Throws ConfigError naming the
// quilt (`quiltName`, e.g. its file) and the field: the display is not lenticular; fewer than 2 or more than 4096
// views; tiles under 2 x 2 pixels; the quilt's render aspect (W/H of its cameras) more than 1 % from the panel's
// screenW/screenH (views rendered for another display: their pixels would land stretched on this one).
void checkQuiltFitsDisplay(const QuiltLayout& layout, const DisplayConfig& display, std::string_view quiltName);

// The part of checkQuiltFitsDisplay that needs no display: 2 to 4096 views, tiles of at least 2 x 2 pixels.
void checkQuiltTiles(const QuiltLayout& layout, std::string_view quiltName);

// The native panel image (screenW x screenH linear RGBA, row 0 = top, alpha 1; the layout of a direct lenticular
// render) of the views under `params` (makeLenticularParams; only its phase, panel and flip fields are used).
// Rows run on `threads` threads. Throws Error if the views are empty or do not fit their image.
std::vector<float> interleaveQuilt(const QuiltViews& views, const gpu_shared::LenticularParams& params,
                                   QuiltViewFilter filter, unsigned threads = 0);

}  // namespace ht
