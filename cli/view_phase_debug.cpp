// view_phase_debug.cpp - see view_phase_debug.h.
#include "cli/view_phase_debug.h"

#include <chrono>

#include "camera_models/lenticular_model.h"

namespace ht::cli {

gpu::RenderResult renderViewPhaseDebug(const gpu_shared::LenticularParams& params) {
  const auto start = std::chrono::steady_clock::now();
  gpu::RenderResult result;
  result.width = static_cast<std::uint32_t>(params.panel.x);
  result.height = static_cast<std::uint32_t>(params.panel.y);
  result.rgba.resize(std::size_t(result.width) * result.height * 4);
  for (std::uint32_t row = 0; row < result.height; ++row) {
    const std::uint32_t y = result.height - 1 - row;  // the model counts y from the bottom (docs/OPTICS.md §0)
    float* dst = result.rgba.data() + std::size_t(row) * result.width * 4;
    for (std::uint32_t x = 0; x < result.width; ++x, dst += 4) {
      for (std::uint32_t c = 0; c < 3; ++c)
        dst[c] = gpu_shared::lenticular_view_phase(params, x, y, c, glm::vec2(0.5f));
      dst[3] = 1.0f;
    }
  }
  result.totalMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace ht::cli
