// simulated_view_projector.cpp - simulateProjectorView and projectorViewConeEyes (formulas in simulated_view.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "camera_models/projector_model.h"
#include "camera_models/simulated_view.h"
#include "common/error.h"
#include "common/parallel_chunks.h"

namespace ht {
namespace {

// One projector's inverse mapping: screen point -> its pixel (y from the bottom), and where light leaves from.
struct ProjectorInverse {
  glm::dmat3 screenToPixel{1.0};  // inverse homography
  glm::dvec3 position{0.0};
  glm::dvec2 imageSize{0.0};  // its image (px)
  glm::dvec2 size{0.0};       // the part of it inside the frame
};

ProjectorInverse projectorInverse(const gpu_shared::ProjectorArrayParams& p, std::uint32_t k, glm::uvec2 frame) {
  const glm::mat4& m = p.projector[k];
  ProjectorInverse inv;
  inv.screenToPixel = glm::inverse(glm::dmat3(glm::mat3(m)));
  inv.position = glm::dvec3(glm::vec3(m[3]));
  inv.imageSize = glm::dvec2(m[0].w, m[1].w);
  inv.size = glm::min(inv.imageSize, glm::dvec2(frame));
  return inv;
}

// Pixel of projector `inv` that lights screen point s (y from the bottom), through its lens: the homography maps
// ideal pixels (projector_model.h projector_screen_point), the panel pixel sits at the distorted point.
bool pixelOf(const gpu_shared::ProjectorArrayParams& p, const ProjectorInverse& inv, glm::dvec2 s, glm::dvec2& pixel) {
  const glm::dvec3 h = inv.screenToPixel * glm::dvec3(s, 1.0);
  if (!(h.z > 0.0)) return false;
  pixel = glm::dvec2(h) / h.z;
  if (gpu_shared::lens_has_distortion(p.distortion)) {
    const glm::dvec2 c = 0.5 * inv.imageSize + glm::dvec2(p.lens.z, p.lens.w);
    const glm::vec2 normalized = glm::vec2((pixel - c) / double(p.lens.x));
    pixel = c + double(p.lens.x) * glm::dvec2(gpu_shared::brown_conrady_distort(p.distortion, normalized));
  }
  return pixel.x >= 0.0 && pixel.y >= 0.0 && pixel.x < inv.size.x && pixel.y < inv.size.y;
}

// Channel values of projector k's image at pixel position (y from the bottom), bilinear between pixel centres.
glm::vec3 sampleImage(std::span<const float> images, std::uint32_t w, std::uint32_t h, std::uint32_t k,
                      glm::dvec2 pixel) {
  const double fx = pixel.x - 0.5, fy = pixel.y - 0.5;
  const double x0f = std::floor(fx), y0f = std::floor(fy);
  const auto wx = float(fx - x0f), wy = float(fy - y0f);
  const int x0 = std::clamp(int(x0f), 0, int(w) - 1), x1 = std::clamp(int(x0f) + 1, 0, int(w) - 1);
  const int y0 = std::clamp(int(y0f), 0, int(h) - 1), y1 = std::clamp(int(y0f) + 1, 0, int(h) - 1);
  auto at = [&](int x, int yFromBottom) {
    const float* px = &images[((std::size_t(k) * h + std::size_t(int(h) - 1 - yFromBottom)) * w + std::size_t(x)) * 4];
    return glm::vec3(px[0], px[1], px[2]);
  };
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), wx), glm::mix(at(x0, y1), at(x1, y1), wx), wy);
}

// Horizontal angle (atan of dx/dz) of the direction from a to b.
double horizontalAngle(glm::dvec3 from, glm::dvec3 to) { return std::atan2(to.x - from.x, to.z - from.z); }

}  // namespace

SimulatedView simulateProjectorView(const gpu_shared::ProjectorArrayParams& p, glm::dvec2 screenSize, std::uint32_t w,
                                    std::uint32_t h, std::span<const float> images, glm::dvec3 eye, glm::uvec2 outSize,
                                    unsigned threads) {
  const auto count = std::uint32_t(p.observer.w);
  const std::size_t floats = std::size_t(w) * h * count * 4;
  if (w == 0 || h == 0 || count == 0 || count > gpu_shared::HT_MAX_PROJECTORS || images.size() != floats) {
    throw Error("simulateProjectorView: " + std::to_string(count) + " projector images of " + std::to_string(w) + "x" +
                std::to_string(h) + " need " + std::to_string(floats) + " floats, got " +
                std::to_string(images.size()));
  }
  if (outSize.x == 0 || outSize.y == 0 || !(screenSize.x > 0.0 && screenSize.y > 0.0)) {
    throw Error("simulateProjectorView: the output and the screen need a size > 0");
  }
  if (!(eye.z > 0.0) || !std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z)) {
    throw Error("simulateProjectorView: the eye must be finite and in front of the screen (z > 0)");
  }
  std::vector<ProjectorInverse> inverse;
  for (std::uint32_t k = 0; k < count; ++k) inverse.push_back(projectorInverse(p, k, {w, h}));
  const double scatter = p.observer.z, norm = gpu_shared::HT_PROJECTOR_SCATTER_NORM;
  const double falloff = scatter > 0.0 ? norm * norm / (scatter * scatter) : 0.0;
  SimulatedView view{outSize.x, outSize.y, std::vector<float>(std::size_t(outSize.x) * outSize.y * 4, 0.0f)};
  forEachChunkParallel(outSize.y, 8, threads == 0 ? hardwareThreads() : threads, [&](std::size_t b, std::size_t e) {
    std::vector<std::pair<double, glm::vec3>> lit;  // (dA, value) of the projectors covering the point
    for (auto y = std::uint32_t(b); y < e; ++y) {
      for (std::uint32_t x = 0; x < outSize.x; ++x) {
        const glm::dvec3 s(((x + 0.5) / outSize.x - 0.5) * screenSize.x, ((y + 0.5) / outSize.y - 0.5) * screenSize.y,
                           0.0);
        const double eyeAngle = horizontalAngle(s, eye);
        lit.clear();
        double leastMiss = std::numeric_limits<double>::infinity();
        for (std::uint32_t k = 0; k < count; ++k) {
          glm::dvec2 pixel;
          if (!pixelOf(p, inverse[k], glm::dvec2(s), pixel)) continue;
          const double dA = horizontalAngle(inverse[k].position, s) - eyeAngle;
          lit.emplace_back(dA, sampleImage(images, w, h, k, pixel));
          leastMiss = std::min(leastMiss, std::fabs(dA));
        }
        if (lit.empty()) continue;
        glm::dvec3 sum(0.0);
        double weights = 0.0;
        for (const auto& [dA, value] : lit) {
          // Relative to the best projector's weight, so a far eye never divides 0 by 0.
          const double weight = falloff > 0.0 ? std::exp(-(dA * dA - leastMiss * leastMiss) * falloff)
                                              : (std::fabs(dA) == leastMiss ? 1.0 : 0.0);
          sum += weight * glm::dvec3(value);
          weights += weight;
        }
        // Brightness toward the eye: the absolute weights, 1 = one projector aimed straight at it.
        const double brightness = falloff > 0.0 ? weights * std::exp(-leastMiss * leastMiss * falloff) : 1.0;
        float* out = &view.rgba[(std::size_t(outSize.y - 1 - y) * outSize.x + x) * 4];
        const glm::dvec3 mean = sum / weights;
        out[0] = float(mean.x), out[1] = float(mean.y), out[2] = float(mean.z);
        out[3] = float(std::min(1.0, brightness));
      }
    }
  });
  return view;
}

std::vector<glm::dvec3> projectorViewConeEyes(const gpu_shared::ProjectorArrayParams& p, std::uint32_t count) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::uint32_t k = 0; k < std::uint32_t(p.observer.w); ++k) {
    const double angle = horizontalAngle(glm::dvec3(glm::vec3(p.projector[k][3])), glm::dvec3(0.0));
    lo = std::min(lo, angle), hi = std::max(hi, angle);
  }
  std::vector<glm::dvec3> eyes;
  if (!(lo <= hi)) return eyes;
  const double distance = p.observer.x;
  for (std::uint32_t i = 0; i < count; ++i) {
    const double angle = lo + (hi - lo) * (i + 0.5) / count;
    eyes.emplace_back(distance * std::tan(angle), p.observer.y, distance);
  }
  return eyes;
}

}  // namespace ht
