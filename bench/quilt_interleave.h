// quilt_interleave.h - CPU implementation of the vendor quilt -> panel interleave (optics.md §3, §4.1): every
// subpixel (x, y, c) of the panel takes the view phase t of the shared lenticular model at the subpixel centre
// (lenticular_view_phase(p, x, y, c, xi = (0.5, 0.5)): classic/Gen3 offsets, BGR, invView all included) and samples
// the quilt views at the pixel's own uv (the same for the three channels, optics.md §4.1; mirrored like the direct
// path when flipImageX/Y), bilinearly inside the tile (clamped to the tile's edge). Rows run on all cores.
//
// View filters (z = t*N, N views, view i's camera sits at t = (i + 0.5)/N, quilt_model.h):
//   Nearest      view floor(z) (holoplaycore.js filterMode 0)
//   VendorLerp   mix(view floor(z), view floor(z)+1, fract(z)) (filterMode 1, looking-glass-webxr's default;
//                HoloPlayCore C `mix(col1, col2, z - floor(z))`), neighbour clamped to N-1
//   CentredLerp  the same lerp on z - 0.5, i.e. between the two views whose cameras bracket t (not vendor)
#pragma once
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "camera_models/camera_params.h"

namespace ht::bench {

enum class QuiltViewFilter { Nearest, VendorLerp, CentredLerp };
std::string_view quiltViewFilterName(QuiltViewFilter filter);  // "nearest", "vendor-lerp", "centred-lerp"

// The N views of a quilt render (RenderResult of Renderer::renderQuilt): view-major, width x height each, linear
// RGBA float, row 0 = the view's top.
struct QuiltViews {
  std::uint32_t width = 0, height = 0, views = 0;
  std::span<const float> rgba;
};

// Panel image in the layout of Renderer::renderLenticular (screenW x screenH RGBA, row 0 = top, alpha 1).
// Throws ht::Error if the views are empty or rgba is not width * height * views * 4 floats.
std::vector<float> interleaveQuilt(const QuiltViews& quilt, const gpu_shared::LenticularParams& params,
                                   QuiltViewFilter filter);

}  // namespace ht::bench
