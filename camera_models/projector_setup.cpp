// projector_setup.cpp - placement, ProjectorArrayParams and the double reference of the HPO model.
#include "camera_models/projector_setup.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "camera_models/lens_distortion_params.h"
#include "common/error.h"

namespace ht {

namespace {

constexpr double kAutoScatteringFactor = 1.5;  // "rule of thumb", LightFieldDisplayModel GenerateSampleModels

const ProjectorArrayConfig& requireProjectorArray(const DisplayConfig& config) {
  if (config.model != DisplayModel::ProjectorArray || !config.projectorArray)
    throw ConfigError(config.sourcePath, "model", "\"" + std::string(displayModelName(config.model)) + "\"",
                      "expected model \"projector-array\" with a projectorArray section");
  return *config.projectorArray;
}

}  // namespace

ProjectorPlacement resolveProjectorPlacement(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const ProjectorArrayConfig& array = requireProjectorArray(config);
  return resolveScreenPlacement(config, sceneBounds, array.screenWidth, array.screenHeight);
}

double resolveAngularScattering(const ProjectorArrayConfig& array) {
  if (array.angularScattering) return *array.angularScattering;
  if (array.projectors.size() < 2) return 0.0;
  std::vector<double> angles;
  for (const ProjectorConfig& projector : array.projectors)
    angles.push_back(std::atan(projector.position.x / -projector.position.z));
  std::sort(angles.begin(), angles.end());
  const std::size_t mid = angles.size() / 2;
  return kAutoScatteringFactor * (angles[mid] - angles[mid - 1]);
}

std::array<double, 9> projectorHomography(const ProjectorArrayConfig& array, std::uint32_t k) {
  const ProjectorConfig& projector = array.projectors.at(k);
  if (projector.homography) return *projector.homography;
  return linearProjectorMapping(array.screenWidth, array.screenHeight, projector.width, projector.height);
}

gpu_shared::ProjectorArrayParams makeProjectorArrayParams(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const ProjectorArrayConfig& array = requireProjectorArray(config);
  const ProjectorPlacement placement = resolveProjectorPlacement(config, sceneBounds);
  gpu_shared::ProjectorArrayParams p{};
  p.observer = glm::vec4(glm::dvec4(array.observerDistance, array.observerHeight, resolveAngularScattering(array),
                                    static_cast<double>(array.projectors.size())));
  p.scale = glm::vec4(static_cast<float>(placement.scale), 0.0f, 0.0f, 0.0f);
  p.localToWorld = glm::mat4(1.0f);
  p.localToWorld[3] = glm::vec4(glm::dvec4(placement.target, 1.0));
  for (std::uint32_t k = 0; k < array.projectors.size(); ++k) {
    const ProjectorConfig& projector = array.projectors[k];
    const std::array<double, 9> h = projectorHomography(array, k);
    glm::mat4& m = p.projector[k];
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) m[c][r] = static_cast<float>(h[static_cast<std::size_t>(r * 3 + c)]);
    m[0].w = static_cast<float>(projector.width);
    m[1].w = static_cast<float>(projector.height);
    m[2].w = 0.0f;
    m[3] = glm::vec4(glm::dvec4(projector.position, 1.0));
  }
  if (array.lens) {
    // The largest normalized radius any projector's image reaches, for the fold check.
    const ProjectorArrayConfig::Lens& lens = *array.lens;
    glm::dvec2 half(0.0);
    for (const ProjectorConfig& projector : array.projectors) {
      half = glm::max(half, (0.5 * glm::dvec2(projector.width, projector.height) + glm::abs(lens.principalOffsetPx)) /
                                lens.focalLengthPx);
    }
    p.lens = glm::vec4(glm::dvec4(lens.focalLengthPx, 0.0, lens.principalOffsetPx.x, lens.principalOffsetPx.y));
    p.distortion = makeLensDistortion(lens.distortion, half, config.sourcePath, "projectorArray.lens.distortion");
  }
  return p;
}

ProjectorArrayReference::ProjectorArrayReference(const DisplayConfig& config, const Bounds3& sceneBounds)
    : array_(requireProjectorArray(config)), placement_(resolveProjectorPlacement(config, sceneBounds)) {}

glm::dvec3 ProjectorArrayReference::screenPoint(std::uint32_t projector, glm::dvec2 pixel) const {
  if (array_.lens && array_.lens->distortion.any()) {  // the ideal pixel behind the lens (projector_model.h)
    const ProjectorConfig& p = array_.projectors.at(projector);
    const glm::dvec2 c = 0.5 * glm::dvec2(p.width, p.height) + array_.lens->principalOffsetPx;
    const double f = array_.lens->focalLengthPx;
    pixel = c + f * undistortReference(array_.lens->distortion, (pixel - c) / f);
  }
  const std::array<double, 9> h = projectorHomography(array_, projector);
  const double w = h[6] * pixel.x + h[7] * pixel.y + h[8];
  return {(h[0] * pixel.x + h[1] * pixel.y + h[2]) / w, (h[3] * pixel.x + h[4] * pixel.y + h[5]) / w, 0.0};
}

ReferenceRay ProjectorArrayReference::ray(std::uint32_t x, std::uint32_t y, std::uint32_t projector,
                                          glm::dvec2 xi) const {
  // Doronin RenderProjector / Jones 2007 (docs/OPTICS.md §6, §9 M3).
  const glm::dvec3 s = screenPoint(projector, {x + xi.x, y + xi.y});
  const glm::dvec3 position = array_.projectors.at(projector).position;
  const double ox = s.x - (s.x - position.x) / position.z * array_.observerDistance;
  const glm::dvec3 origin(ox, array_.observerHeight, array_.observerDistance);
  return {placement_.target + placement_.scale * origin, glm::normalize(s - origin)};
}

}  // namespace ht
