// quilt_interleave.cpp - see quilt_interleave.h.
#include "camera_models/quilt_interleave.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "camera_models/lenticular_model.h"
#include "common/error.h"
#include "common/parallel_chunks.h"

namespace ht {
namespace {

constexpr std::uint32_t kMaxQuiltViews = 4096;
constexpr double kAspectTolerance = 0.01;  // relative; quilt names carry the aspect with 2-4 decimals

std::string sizeText(std::uint32_t w, std::uint32_t h) { return std::to_string(w) + "x" + std::to_string(h); }

void checkImageSize(const char* what, std::uint32_t w, std::uint32_t h, std::size_t floats) {
  if (w == 0 || h == 0 || floats != std::size_t(w) * h * 4) {
    throw Error(std::string(what) + ": an image of " + sizeText(w, h) + " RGBA pixels needs " +
                std::to_string(std::size_t(w) * h * 4) + " floats, got " + std::to_string(floats));
  }
}

// Channel c of view `view` at tile uv (u, v), v from the bottom, bilinear, clamped to the tile's edge pixels.
float sampleView(const QuiltViews& q, std::uint32_t view, float u, float v, std::uint32_t c) {
  const float fx = u * float(q.tileWidth) - 0.5f, fy = v * float(q.tileHeight) - 0.5f;
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float wx = fx - x0f, wy = fy - y0f;
  const int maxX = int(q.tileWidth) - 1, maxY = int(q.tileHeight) - 1;
  const int x0 = std::clamp(int(x0f), 0, maxX), x1 = std::clamp(int(x0f) + 1, 0, maxX);
  const int y0 = std::clamp(int(y0f), 0, maxY), y1 = std::clamp(int(y0f) + 1, 0, maxY);
  const glm::uvec2 topLeft = q.tileTopLeft[view];
  auto at = [&](int x, int yFromBottom) {  // image rows are stored top first
    const std::size_t row = topLeft.y + std::size_t(maxY - yFromBottom), column = topLeft.x + std::size_t(x);
    return q.rgba[4 * (row * q.imageWidth + column) + c];
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
void interleaveRow(const QuiltViews& q, const gpu_shared::LenticularParams& p, QuiltViewFilter filter, std::uint32_t y,
                   std::vector<float>& panel) {
  const auto w = std::uint32_t(p.panel.x), h = std::uint32_t(p.panel.y);
  float v = (float(y) + 0.5f) / float(h);
  if (p.flags.w != 0) v = 1.0f - v;
  float* row = &panel[std::size_t(h - 1 - y) * w * 4];
  for (std::uint32_t x = 0; x < w; ++x) {
    float u = (float(x) + 0.5f) / float(w);
    if (p.flags.z != 0) u = 1.0f - u;
    for (std::uint32_t c = 0; c < 3; ++c) {
      const float t = gpu_shared::lenticular_view_phase(p, x, y, c, glm::vec2(0.5f));
      const ViewBlend blend = blendFor(t, q.views(), filter);
      const float a = sampleView(q, blend.a, u, v, c);
      const float b = blend.weightB > 0.0f ? sampleView(q, blend.b, u, v, c) : a;
      row[4 * x + c] = a + (b - a) * blend.weightB;
    }
  }
}

void checkViews(const QuiltViews& q) {
  checkImageSize("interleaveQuilt", q.imageWidth, q.imageHeight, q.rgba.size());
  if (q.views() == 0 || q.tileWidth == 0 || q.tileHeight == 0) {
    throw Error("interleaveQuilt: " + std::to_string(q.views()) + " views of " + sizeText(q.tileWidth, q.tileHeight) +
                " pixels: nothing to sample");
  }
  for (std::uint32_t i = 0; i < q.views(); ++i) {
    const glm::uvec2 tl = q.tileTopLeft[i];
    if (std::uint64_t(tl.x) + q.tileWidth > q.imageWidth || std::uint64_t(tl.y) + q.tileHeight > q.imageHeight) {
      throw Error("interleaveQuilt: view " + std::to_string(i) + " at (" + std::to_string(tl.x) + ", " +
                  std::to_string(tl.y) + ") of " + sizeText(q.tileWidth, q.tileHeight) + " leaves the " +
                  sizeText(q.imageWidth, q.imageHeight) + " image");
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

QuiltViewFilter parseQuiltViewFilter(std::string_view name) {
  for (QuiltViewFilter f : {QuiltViewFilter::Nearest, QuiltViewFilter::VendorLerp, QuiltViewFilter::CentredLerp}) {
    if (name == quiltViewFilterName(f)) return f;
  }
  if (name == "vendor") return QuiltViewFilter::VendorLerp;
  if (name == "centred" || name == "centered" || name == "centered-lerp") return QuiltViewFilter::CentredLerp;
  throw UsageError("unknown quilt view filter '" + std::string(name) +
                   "' (expected nearest, vendor-lerp or centred-lerp)");
}

QuiltViews quiltImageViews(const QuiltLayout& layout, std::span<const float> rgba) {
  checkImageSize("quilt image", layout.quiltWidth, layout.quiltHeight, rgba.size());
  QuiltViews q{layout.quiltWidth, layout.quiltHeight, layout.tileWidth, layout.tileHeight, {}, rgba};
  for (std::uint32_t i = 0; i < layout.views(); ++i) {
    const glm::uvec2 bottomLeft = quiltTileOrigin(layout, i);
    q.tileTopLeft.emplace_back(bottomLeft.x, layout.quiltHeight - bottomLeft.y - layout.tileHeight);
  }
  return q;
}

QuiltViews viewStackViews(std::uint32_t width, std::uint32_t height, std::uint32_t views, std::span<const float> rgba) {
  checkImageSize("view stack", width, height * views, rgba.size());
  QuiltViews q{width, height * views, width, height, {}, rgba};
  for (std::uint32_t i = 0; i < views; ++i) q.tileTopLeft.emplace_back(0u, i * height);
  return q;
}

void checkQuiltTiles(const QuiltLayout& layout, std::string_view quiltName) {
  const std::string name(quiltName);
  const std::string tiles = std::to_string(layout.columns) + "x" + std::to_string(layout.rows);
  if (layout.views() < 2 || layout.views() > kMaxQuiltViews) {
    throw ConfigError(name, "quilt tiles", tiles,
                      "expected 2 to " + std::to_string(kMaxQuiltViews) + " views (columns x rows)");
  }
  if (layout.tileWidth < 2 || layout.tileHeight < 2) {
    throw ConfigError(name, "quilt size", sizeText(layout.quiltWidth, layout.quiltHeight),
                      "its " + tiles + " tiles are " + sizeText(layout.tileWidth, layout.tileHeight) +
                          " pixels; each view needs at least 2x2");
  }
}

void checkQuiltFitsDisplay(const QuiltLayout& layout, const DisplayConfig& display, std::string_view quiltName) {
  const std::string name(quiltName);
  if (display.model != DisplayModel::Lenticular || !display.calibration) {
    throw ConfigError(display.sourcePath, "model", std::string(displayModelName(display.model)),
                      "a quilt is interleaved for a lenticular (Looking Glass) display only");
  }
  checkQuiltTiles(layout, quiltName);
  const LookingGlassCalibration& c = *display.calibration;
  const double panelAspect = double(c.screenW) / double(c.screenH);
  if (!(std::fabs(layout.aspect / panelAspect - 1.0) <= kAspectTolerance)) {
    throw ConfigError(name, "quilt aspect", std::to_string(layout.aspect),
                      "the display's aspect is " + std::to_string(panelAspect) + " (" + sizeText(c.screenW, c.screenH) +
                          "); this quilt was rendered for another display (re-render it for this one, or name the "
                          "right display)");
  }
}

std::vector<float> interleaveQuilt(const QuiltViews& q, const gpu_shared::LenticularParams& p, QuiltViewFilter filter,
                                   unsigned threads) {
  checkViews(q);
  const auto w = std::uint32_t(p.panel.x), h = std::uint32_t(p.panel.y);
  std::vector<float> panel(std::size_t(w) * h * 4, 1.0f);
  forEachChunkParallel(h, 16, threads == 0 ? hardwareThreads() : threads, [&](std::size_t begin, std::size_t end) {
    for (auto y = std::uint32_t(begin); y < end; ++y) interleaveRow(q, p, filter, y, panel);
  });
  return panel;
}

}  // namespace ht
