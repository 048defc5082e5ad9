// quilt_interleave.cpp - see quilt_interleave.h.
#include "bench/quilt_interleave.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>

#include "bench/parallel_tiles.h"

#include "camera_models/lenticular_model.h"
#include "common/error.h"

namespace ht::bench {
namespace {

// Channel c of view `view` at tile uv (u, v), v from the bottom, bilinear with clamp-to-edge.
float sampleView(const QuiltViews& q, std::uint32_t view, float u, float v, int c) {
  const float fx = u * float(q.width) - 0.5f, fy = v * float(q.height) - 0.5f;
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float wx = fx - x0f, wy = fy - y0f;
  const int maxX = int(q.width) - 1, maxY = int(q.height) - 1;
  const int x0 = std::clamp(int(x0f), 0, maxX), x1 = std::clamp(int(x0f) + 1, 0, maxX);
  const int y0 = std::clamp(int(y0f), 0, maxY), y1 = std::clamp(int(y0f) + 1, 0, maxY);
  const std::size_t base = std::size_t(view) * q.width * q.height;
  auto at = [&](int x, int yFromBottom) {  // rows are stored top first
    return q.rgba[4 * (base + std::size_t(maxY - yFromBottom) * q.width + std::size_t(x)) + std::size_t(c)];
  };
  const float bottom = at(x0, y0) * (1.0f - wx) + at(x1, y0) * wx;
  const float top = at(x0, y1) * (1.0f - wx) + at(x1, y1) * wx;
  return bottom * (1.0f - wy) + top * wy;
}

struct ViewBlend {
  std::uint32_t a = 0, b = 0;
  float weightB = 0.0f;
};

ViewBlend blendFor(float t, std::uint32_t views, QuiltViewFilter filter) {
  const float n = float(views);
  const float z = filter == QuiltViewFilter::CentredLerp ? t * n - 0.5f : t * n;
  const float zf = std::floor(z);
  const auto clampView = [&](float i) { return std::uint32_t(std::clamp(i, 0.0f, n - 1.0f)); };
  if (filter == QuiltViewFilter::Nearest) return {clampView(zf), clampView(zf), 0.0f};
  return {clampView(zf), clampView(zf + 1.0f), z - zf};
}

// Panel row y (from the bottom; stored at row h-1-y).
void interleaveRow(const QuiltViews& q, const gpu_shared::LenticularParams& p, QuiltViewFilter filter,
                   std::uint32_t y, std::vector<float>& panel) {
  const auto w = std::uint32_t(p.panel.x), h = std::uint32_t(p.panel.y);
  float v = (float(y) + 0.5f) / float(h);
  if (p.flags.w != 0) v = 1.0f - v;
  float* row = &panel[std::size_t(h - 1 - y) * w * 4];
  for (std::uint32_t x = 0; x < w; ++x) {
    float u = (float(x) + 0.5f) / float(w);
    if (p.flags.z != 0) u = 1.0f - u;
    for (std::uint32_t c = 0; c < 3; ++c) {
      const float t = gpu_shared::lenticular_view_phase(p, x, y, c, glm::vec2(0.5f));
      const ViewBlend blend = blendFor(t, q.views, filter);
      const float a = sampleView(q, blend.a, u, v, int(c));
      const float b = blend.weightB > 0.0f ? sampleView(q, blend.b, u, v, int(c)) : a;
      row[4 * x + c] = a + (b - a) * blend.weightB;
    }
  }
}

}  // namespace

std::string_view quiltViewFilterName(QuiltViewFilter filter) {
  switch (filter) {
    case QuiltViewFilter::Nearest: return "nearest";
    case QuiltViewFilter::VendorLerp: return "vendor-lerp";
    case QuiltViewFilter::CentredLerp: return "centred-lerp";
  }
  return "?";
}

std::vector<float> interleaveQuilt(const QuiltViews& q, const gpu_shared::LenticularParams& p,
                                   QuiltViewFilter filter) {
  if (q.views == 0 || q.width == 0 || q.height == 0 || q.rgba.size() != std::size_t(q.width) * q.height * q.views * 4) {
    throw Error("interleaveQuilt: quilt of " + std::to_string(q.views) + " views of " + std::to_string(q.width) + "x" +
                std::to_string(q.height) + " does not match " + std::to_string(q.rgba.size()) + " floats");
  }
  const auto w = std::uint32_t(p.panel.x), h = std::uint32_t(p.panel.y);
  std::vector<float> panel(std::size_t(w) * h * 4, 1.0f);
  auto rows = [&](std::size_t begin, std::size_t end) {
    for (auto y = std::uint32_t(begin); y < end; ++y) interleaveRow(q, p, filter, y, panel);
  };
  forEachChunkParallel(h, 16, std::max(1u, std::thread::hardware_concurrency()), rows);
  return panel;
}

}  // namespace ht::bench
