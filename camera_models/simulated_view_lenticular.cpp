// simulated_view_lenticular.cpp - simulateLenticularView and lenticularViewConeEyes (formulas in simulated_view.h).
#include <algorithm>
#include <cmath>
#include <string>

#include "camera_models/lenticular_model.h"
#include "camera_models/simulated_view.h"
#include "common/error.h"
#include "common/parallel_chunks.h"

namespace ht {
namespace {

constexpr int kMaxRowsEitherWay = 8;

// The phase an eye needs at focal-plane x coordinate px (lenticular_model.h frame): the virtual camera where the line
// from (px, 0) through the eye meets z = D.
double eyePhase(const gpu_shared::LenticularParams& p, glm::dvec3 eye, double px) {
  const double d = p.camera.x;
  const double cameraX = px + (eye.x - px) * d / eye.z;
  return std::atan(cameraX / d) / double(p.camera.w) + 0.5;
}

// miss_s = t_s - t_eye(P_s) wrapped to [-1/2, 1/2) for every subpixel, index (y * W + x) * 3 + c, y from the bottom.
std::vector<float> subpixelMisses(const gpu_shared::LenticularParams& p, glm::dvec3 eye, unsigned threads) {
  const auto w = std::uint32_t(p.panel.x), h = std::uint32_t(p.panel.y);
  const double aspect = p.camera.z, size = p.camera.y;
  std::vector<float> miss(std::size_t(w) * h * 3);
  forEachChunkParallel(h, 8, threads, [&](std::size_t begin, std::size_t end) {
    for (auto y = std::uint32_t(begin); y < end; ++y) {
      for (std::uint32_t x = 0; x < w; ++x) {
        for (std::uint32_t c = 0; c < 3; ++c) {
          const glm::vec2 o = gpu_shared::lenticular_sample_offset_px(p, x, y, c, glm::vec2(0.5f));
          double u = gpu_shared::lenticular_uv_at_offset(p, x, y, o).x;
          if (p.flags.z != 0) u = 1.0 - u;  // flipImageX mirrors the focal point, as lenticular_ray_for_phase does
          const double t = gpu_shared::lenticular_view_phase_at_offset(p, x, y, o);
          const double m = t - eyePhase(p, eye, (u - 0.5) * aspect * size);
          miss[(std::size_t(y) * w + x) * 3 + c] = float(m - std::floor(m + 0.5));
        }
      }
    }
  });
  return miss;
}

struct LensWalk {
  double slant = 0.0;     // -B/A: pixels the constant-phase line moves per row
  int halfPeriod = 1;     // ceil(1/(2|A|)) candidates either side of the line
  int rowsEitherWay = 1;  // rows searched either way for a crossing
  float crossing = 0.0f;  // |A|/6: half a subpixel's phase width
};

LensWalk lensWalk(const gpu_shared::LenticularParams& p) {
  const double a = double(p.phase.x) / p.panel.x;              // phase per pixel in x
  const double b = double(p.phase.y) * p.phase.x / p.panel.y;  // phase per pixel in y
  LensWalk walk;
  walk.slant = -b / a;
  walk.halfPeriod = std::clamp(int(std::ceil(0.5 / std::fabs(a))), 1, int(p.panel.x));
  const double rowsPerCycle = std::fabs(b) > 0.0 ? std::fabs(a) / std::fabs(b) : 2.0 * kMaxRowsEitherWay;
  walk.rowsEitherWay = std::clamp(int(std::ceil(0.5 * rowsPerCycle)) + 1, 1, kMaxRowsEitherWay);
  walk.crossing = float(std::fabs(a) / 6.0);
  return walk;
}

struct Candidate {
  float miss = 1.0f;
  std::uint32_t x = 0, y = 0;
};

// The channel-c subpixel of least |miss| in row y within half a lens period of column xc.
Candidate bestInRow(const std::vector<float>& miss, std::uint32_t w, std::uint32_t y, double xc, int halfPeriod,
                    std::uint32_t c) {
  Candidate best;
  const int centre = int(std::lround(xc));
  for (int x = std::max(0, centre - halfPeriod); x <= std::min(int(w) - 1, centre + halfPeriod); ++x) {
    const float m = std::fabs(miss[(std::size_t(y) * w + std::uint32_t(x)) * 3 + c]);
    if (m < best.miss) best = {m, std::uint32_t(x), y};
  }
  return best;
}

Candidate seenSubpixel(const std::vector<float>& miss, std::uint32_t w, std::uint32_t h, const LensWalk& walk,
                       std::uint32_t x, std::uint32_t y, std::uint32_t c) {
  Candidate fallback = bestInRow(miss, w, y, x, walk.halfPeriod, c);
  if (fallback.miss <= walk.crossing) return fallback;
  for (int k = 1; k <= walk.rowsEitherWay; ++k) {
    Candidate pair;
    for (int row : {int(y) + k, int(y) - k}) {
      if (row < 0 || row >= int(h)) continue;
      const double xc = x + walk.slant * (row - int(y));
      const Candidate cand = bestInRow(miss, w, std::uint32_t(row), xc, walk.halfPeriod, c);
      if (cand.miss < pair.miss) pair = cand;
    }
    if (pair.miss <= walk.crossing) return pair;
    if (pair.miss < fallback.miss) fallback = pair;
  }
  return fallback;
}

}  // namespace

SimulatedView simulateLenticularView(const gpu_shared::LenticularParams& p, std::span<const float> panel,
                                     glm::dvec3 eye, unsigned threads) {
  const auto w = std::uint32_t(p.panel.x), h = std::uint32_t(p.panel.y);
  if (panel.size() != std::size_t(w) * h * 4) {
    throw Error("simulateLenticularView: the panel is " + std::to_string(w) + "x" + std::to_string(h) + " (needs " +
                std::to_string(std::size_t(w) * h * 4) + " floats), got " + std::to_string(panel.size()));
  }
  if (!(eye.z > 0.0) || !std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z)) {
    throw Error("simulateLenticularView: the eye must be finite and in front of the display (z > 0)");
  }
  threads = threads == 0 ? hardwareThreads() : threads;
  const std::vector<float> miss = subpixelMisses(p, eye, threads);
  const LensWalk walk = lensWalk(p);
  SimulatedView view{w, h, std::vector<float>(std::size_t(w) * h * 4, 1.0f)};
  forEachChunkParallel(h, 8, threads, [&](std::size_t begin, std::size_t end) {
    for (auto y = std::uint32_t(begin); y < end; ++y) {
      float* out = &view.rgba[std::size_t(h - 1 - y) * w * 4];
      for (std::uint32_t x = 0; x < w; ++x) {
        for (std::uint32_t c = 0; c < 3; ++c) {
          const Candidate seen = seenSubpixel(miss, w, h, walk, x, y, c);
          out[4 * x + c] = panel[(std::size_t(h - 1 - seen.y) * w + seen.x) * 4 + c];
        }
      }
    }
  });
  return view;
}

std::vector<glm::dvec3> lenticularViewConeEyes(const gpu_shared::LenticularParams& p, std::uint32_t count) {
  std::vector<glm::dvec3> eyes;
  const double d = p.camera.x;
  for (std::uint32_t i = 0; i < count; ++i) {
    const double t = (i + 0.5) / count;
    eyes.emplace_back(d * std::tan(double(p.camera.w) * (t - 0.5)), 0.0, d);
  }
  return eyes;
}

}  // namespace ht
