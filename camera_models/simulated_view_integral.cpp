// simulated_view_integral.cpp - simulateIntegralView and integralViewConeEyes (formulas in simulated_view.h).
#include <algorithm>
#include <cmath>
#include <string>

#include "camera_models/integral_model.h"
#include "camera_models/simulated_view.h"
#include "common/error.h"
#include "common/parallel_chunks.h"

namespace ht {
namespace {

constexpr int kApertureGrid = 4;  // "aperture" sampling: kApertureGrid^2 points over the lens

// LCD pixel coordinates (y up) of point q (display units).
glm::dvec2 lcdPixel(const gpu_shared::IntegralParams& p, glm::dvec2 q) {
  return {q.x / p.panel.z + 0.5 * p.panel.x, q.y / p.panel.z + 0.5 * p.panel.y};
}

bool onLcd(const gpu_shared::IntegralParams& p, glm::dvec2 pixel) {
  return pixel.x >= 0.0 && pixel.y >= 0.0 && pixel.x < p.panel.x && pixel.y < p.panel.y;
}

// Channel ch of the LCD at pixel coordinates (px, py) on it, bilinear between the channel's stripe-subpixel centres
// (x + (ch + 0.5)/3, y + 0.5).
float sampleLcd(const gpu_shared::IntegralParams& p, std::span<const float> lcd, glm::dvec2 pixel, std::uint32_t ch) {
  const auto w = int(p.panel.x), h = int(p.panel.y);
  const double px = pixel.x, py = pixel.y;
  const double gx = px - (ch + 0.5) / 3.0, gy = py - 0.5;
  const double x0f = std::floor(gx), y0f = std::floor(gy);
  const auto wx = float(gx - x0f), wy = float(gy - y0f);
  const int x0 = std::clamp(int(x0f), 0, w - 1), x1 = std::clamp(int(x0f) + 1, 0, w - 1);
  const int y0 = std::clamp(int(y0f), 0, h - 1), y1 = std::clamp(int(y0f) + 1, 0, h - 1);
  auto at = [&](int x, int yFromBottom) {
    return lcd[(std::size_t(h - 1 - yFromBottom) * w + std::size_t(x)) * 4 + ch];
  };
  const float bottom = at(x0, y0) * (1.0f - wx) + at(x1, y0) * wx;
  const float top = at(x0, y1) * (1.0f - wx) + at(x1, y1) * wx;
  return bottom * (1.0f - wy) + top * wy;
}

// Points s - c on the lens the eye looks through: the centre, or a grid over the aperture.
std::vector<glm::dvec2> aperturePoints(const gpu_shared::IntegralParams& p) {
  if (p.panel.w <= 0.5f) return {glm::dvec2(0.0)};
  std::vector<glm::dvec2> points;
  for (int j = 0; j < kApertureGrid; ++j) {
    for (int i = 0; i < kApertureGrid; ++i) {
      const glm::vec2 xi((i + 0.5f) / kApertureGrid, (j + 0.5f) / kApertureGrid);
      points.emplace_back(gpu_shared::integral_rotate(p, (xi - glm::vec2(0.5f)) * p.lens.x));
    }
  }
  return points;
}

}  // namespace

SimulatedView simulateIntegralView(const gpu_shared::IntegralParams& p, std::span<const float> lcd, glm::dvec3 eye,
                                   unsigned threads) {
  const auto w = std::uint32_t(p.panel.x), h = std::uint32_t(p.panel.y);
  if (lcd.size() != std::size_t(w) * h * 4) {
    throw Error("simulateIntegralView: the LCD is " + std::to_string(w) + "x" + std::to_string(h) + " (needs " +
                std::to_string(std::size_t(w) * h * 4) + " floats), got " + std::to_string(lcd.size()));
  }
  if (!(eye.z > 0.0) || !std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z)) {
    throw Error("simulateIntegralView: the eye must be finite and in front of the lenses (z > 0)");
  }
  const std::vector<glm::dvec2> aperture = aperturePoints(p);
  const double gap = p.lens.z, focal = p.lens.y;
  SimulatedView view{w, h, std::vector<float>(std::size_t(w) * h * 4, 1.0f)};
  forEachChunkParallel(h, 8, threads == 0 ? hardwareThreads() : threads, [&](std::size_t b, std::size_t e) {
    for (auto y = std::uint32_t(b); y < e; ++y) {
      for (std::uint32_t x = 0; x < w; ++x) {
        const glm::vec2 f(0.5f);
        const glm::dvec2 lens = glm::dvec2(gpu_shared::integral_pixel_position(p, x, y, f)) -
                                glm::dvec2(gpu_shared::integral_lens_offset(p, x, y, f));
        glm::dvec3 sum(0.0);
        std::size_t onPanel = 0;
        for (const glm::dvec2& fromCentre : aperture) {
          const glm::dvec2 s = lens + fromCentre;
          const glm::dvec2 toEye = (glm::dvec2(eye) - s) / eye.z;
          const glm::dvec2 pixel = lcdPixel(p, s - gap * (toEye + fromCentre / focal));
          if (!onLcd(p, pixel)) continue;
          for (std::uint32_t ch = 0; ch < 3; ++ch) sum[ch] += sampleLcd(p, lcd, pixel, ch);
          ++onPanel;
        }
        float* out = &view.rgba[(std::size_t(h - 1 - y) * w + x) * 4];
        for (std::uint32_t ch = 0; ch < 3; ++ch) out[ch] = float(sum[ch] / double(aperture.size()));
        out[3] = float(onPanel) / float(aperture.size());
      }
    }
  });
  return view;
}

std::vector<glm::dvec3> integralViewConeEyes(const gpu_shared::IntegralParams& p, double viewerDistance,
                                             std::uint32_t count) {
  std::vector<glm::dvec3> eyes;
  const double halfSlope = 0.5 * p.lens.x / p.lens.z;
  for (std::uint32_t i = 0; i < count; ++i) {
    const double slope = halfSlope * (2.0 * (i + 0.5) / count - 1.0);
    eyes.emplace_back(viewerDistance * slope, 0.0, viewerDistance);
  }
  return eyes;
}

}  // namespace ht
