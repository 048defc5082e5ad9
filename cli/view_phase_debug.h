// view_phase_debug.h - `holotrace render --debug views`: each subpixel of a lenticular panel shows its own view phase
// t in [0, 1) (0 = leftmost view) as its channel's value, computed with the renderer's ray-generation code
// (camera_models/lenticular_model.h, the same source the GPU runs) at the subpixel's centre. Seen through the lens
// sheet, a correct calibration shows one smooth ramp from the leftmost to the rightmost viewing position; a wrong
// pitch, slope or centre shows bands. No scene and no GPU are needed.
#pragma once
#include "camera_models/camera_params.h"
#include "gpu/renderer.h"

namespace ht::cli {

// RGBA image of the panel (row 0 = top), channel c of pixel (x, y) = view phase of subpixel (x, y, c).
gpu::RenderResult renderViewPhaseDebug(const gpu_shared::LenticularParams& params);

}  // namespace ht::cli
