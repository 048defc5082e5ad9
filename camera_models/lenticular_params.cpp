// lenticular_params.cpp - raw calibration -> shader values -> LenticularParams (docs/OPTICS.md §2, §4.3, §9 M2).
#include "camera_models/lenticular_params.h"

#include <bit>
#include <cmath>
#include <numbers>

#include "camera_models/json_fields.h"
#include "common/error.h"

namespace ht {

namespace {

constexpr double kAutoSizeMargin = 1.1;      // "auto" size: 10 % margin around the bounds' x/y extent
constexpr double kFallbackTargetSize = 2.0;  // looking-glass-webxr default targetDiam

const LookingGlassCalibration& requireLenticular(const DisplayConfig& config) {
  if (config.model != DisplayModel::Lenticular || !config.calibration)
    throw ConfigError(config.sourcePath, "model", "\"" + std::string(displayModelName(config.model)) + "\"",
                      "expected \"lenticular\" with a calibration for a lenticular render");
  return *config.calibration;
}

bool hasArea(const Bounds3& bounds) {
  return !bounds.empty() && (bounds.extent().x > 0.0f || bounds.extent().y > 0.0f);
}

}  // namespace

LenticularShaderValues lenticularShaderValues(const LookingGlassCalibration& c) {
  // docs/OPTICS.md §2 (looking-glass-webxr src/LookingGlassConfig.ts at b44ed27; LKG-Toolkit Calibration.cs
  // ProcessPitch, ProcessSlope). subp is negated with flipImageX as in looking-glass-webxr HEAD.
  const double flip = c.flipImageX ? -1.0 : 1.0;
  const double width = static_cast<double>(c.screenW);
  const double height = static_cast<double>(c.screenH);
  LenticularShaderValues v;
  v.pitch = c.pitch * (width / c.DPI) * std::cos(std::atan(1.0 / c.slope));
  v.tilt = height / (width * c.slope) * flip;
  v.subp = 1.0 / (3.0 * width) * flip;
  v.center = c.center;
  return v;
}

LenticularCamera resolveLenticularCamera(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const LookingGlassCalibration& calibration = requireLenticular(config);
  LenticularCamera camera;
  camera.aspect = static_cast<double>(calibration.screenW) / static_cast<double>(calibration.screenH);
  const bool boundsUsable = hasArea(sceneBounds);
  if (config.camera.target) {
    camera.target = *config.camera.target;
  } else if (boundsUsable) {
    camera.target = glm::dvec3(sceneBounds.lo) + 0.5 * (glm::dvec3(sceneBounds.hi) - glm::dvec3(sceneBounds.lo));
  }
  if (config.camera.size) {
    camera.size = *config.camera.size;
  } else if (boundsUsable) {
    glm::dvec3 extent = glm::dvec3(sceneBounds.hi) - glm::dvec3(sceneBounds.lo);
    camera.size = kAutoSizeMargin * std::max(extent.y, extent.x / camera.aspect);
  } else {
    camera.size = kFallbackTargetSize;
  }
  // looking-glass-webxr LookingGlassXRDevice.ts onFrameStart: D = 0.5 * targetDiam / tan(fovy / 2).
  const double fovy = config.camera.fovyDeg * std::numbers::pi / 180.0;
  camera.focalDistance = 0.5 * camera.size / std::tan(0.5 * fovy);
  // docs/OPTICS.md §2: viewCone_rad = viewCone * depthiness * pi / 180 (full cone, webxr convention).
  camera.viewConeRad = calibration.viewCone * config.camera.depthiness * std::numbers::pi / 180.0;
  return camera;
}

PanelLayout panelLayout(const DisplayConfig& config) {
  const LookingGlassCalibration& calibration = requireLenticular(config);
  return {calibration.screenW, calibration.screenH, calibration.flipSubp};
}

glm::vec2 splitPhaseRate(double rate, std::uint32_t count) {
  if (rate == 0.0 || !std::isfinite(rate)) return {static_cast<float>(rate), 0.0f};
  const int indexBits = static_cast<int>(std::bit_width(count > 0 ? count - 1u : 0u));
  const int hiBits = std::max(1, std::numeric_limits<float>::digits - indexBits);
  int exponent = 0;
  std::frexp(rate, &exponent);  // |rate| = m * 2^exponent, 0.5 <= m < 1
  const double quantum = std::ldexp(1.0, exponent - hiBits);
  const double hi = std::round(rate / quantum) * quantum;  // at most hiBits significant bits: i*hi exact in float
  return {static_cast<float>(hi), static_cast<float>(rate - hi)};
}

gpu_shared::LenticularParams makeLenticularParams(const DisplayConfig& config, const Bounds3& sceneBounds) {
  const LookingGlassCalibration& calibration = requireLenticular(config);
  const LenticularShaderValues shader = lenticularShaderValues(calibration);
  const LenticularCamera camera = resolveLenticularCamera(config, sceneBounds);
  const double width = static_cast<double>(calibration.screenW);
  const double height = static_cast<double>(calibration.screenH);

  gpu_shared::LenticularParams p{};
  p.phase = glm::vec4(glm::dvec4(shader.pitch, shader.tilt, shader.subp, shader.center));
  p.panel = glm::vec4(glm::dvec4(width, height, calibration.invView ? 1.0 : 0.0, calibration.flipSubp ? 1.0 : 0.0));
  p.camera = glm::vec4(glm::dvec4(camera.focalDistance, camera.size, camera.aspect, camera.viewConeRad));
  const bool cellsInUse = calibration.cellPatternMode != 0;
  const int cellCount = cellsInUse ? static_cast<int>(calibration.subpixelCells.size()) : 0;
  p.flags = glm::ivec4(calibration.cellPatternMode, cellCount, calibration.flipImageX ? 1 : 0,
                       calibration.flipImageY ? 1 : 0);
  for (int k = 0; k < cellCount; ++k) {
    for (std::uint32_t c = 0; c < 3; ++c) {
      glm::dvec2 offset = calibration.subpixelCells[static_cast<std::size_t>(k)].offset(c);
      // holoplaycore.js / looking-glass-webxr `get subpixelCells()`: offsets divided by screenW / screenH, once.
      glm::vec4& slot = p.cellOffset[static_cast<std::size_t>(k) * 3 + c];
      slot.x = static_cast<float>(offset.x / width);
      slot.y = static_cast<float>(offset.y / height);
    }
  }
  // Phase rates per pixel, split for exact integer-part removal (lenticular_model.h, lenticular_view_phase):
  // A = pitch_s / W along x, B = tilt * pitch_s / H along y (expanding phi of docs/OPTICS.md §3.1 in x and y).
  const glm::vec2 rateX = splitPhaseRate(shader.pitch / width, calibration.screenW);
  const glm::vec2 rateY = splitPhaseRate(shader.tilt * shader.pitch / height, calibration.screenH);
  p.cellOffset[0].z = rateX.x;
  p.cellOffset[0].w = rateX.y;
  p.cellOffset[1].z = rateY.x;
  p.cellOffset[1].w = rateY.y;
  const glm::dmat4 localToWorld(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0,  //
                                camera.target.x, camera.target.y, camera.target.z, 1.0);
  p.localToWorld = glm::mat4(localToWorld);
  return p;
}

}  // namespace ht
