// lenticular_params.h - from a display config to the GPU parameter block of the lenticular model
// (camera_params.h LenticularParams, consumed by lenticular_model.h).
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "camera_models/camera_params.h"
#include "camera_models/display_config.h"
#include "camera_models/pinhole_params.h"  // makePinholeParams, the other camera model's parameter block
#include "scene/scene.h"

namespace ht {

// Shader uniforms from raw calibration values (docs/OPTICS.md §2; looking-glass-webxr src/LookingGlassConfig.ts):
//   pitch_s = pitch * (screenW / DPI) * cos(atan(1 / slope)),  tilt = screenH / (screenW * slope) * (flipX ? -1 : 1),
//   subp = 1 / (3 * screenW) * (flipX ? -1 : 1),  center unchanged.
struct LenticularShaderValues {
  double pitch = 0.0;  // pitch_s: lenses across the full screen width
  double tilt = 0.0;
  double subp = 0.0;  // one subpixel in u units, signed
  double center = 0.0;
};
LenticularShaderValues lenticularShaderValues(const LookingGlassCalibration& calibration);

// The display's camera resolved against the scene (looking-glass-webxr LookingGlassXRDevice.ts, docs/OPTICS.md §4.3):
// focal rectangle of height `size` and width aspect*size centred on `target`, cameras at distance
// D = 0.5*size/tan(fovy/2), spread over viewCone_rad = viewCone*depthiness*pi/180 (full cone).
// "auto" target = bounds centre; "auto" size = 1.1 * max(extent.y, extent.x/aspect). Empty or flat bounds fall back
// to target (0,0,0) / size 2 (webxr targetDiam default).
struct LenticularCamera {
  glm::dvec3 target{0.0};
  double size = 2.0;
  double focalDistance = 0.0;
  double aspect = 1.0;  // screenW / screenH
  double viewConeRad = 0.0;
};
LenticularCamera resolveLenticularCamera(const DisplayConfig& config, const Bounds3& sceneBounds);

// Native panel image the interleaved render fills.
struct PanelLayout {
  std::uint32_t width = 0, height = 0;
  bool bgr = false;  // flipSubp
};
PanelLayout panelLayout(const DisplayConfig& config);

// Phase rate `rate` (phase per pixel) split as hi + lo, both float, hi with few enough significant bits that
// i*hi is exact in float for every integer i in [0, count): the integer part of i*rate is removed exactly by fract().
glm::vec2 splitPhaseRate(double rate, std::uint32_t count);

// Throws ConfigError if the config is not a lenticular display.
gpu_shared::LenticularParams makeLenticularParams(const DisplayConfig& config, const Bounds3& sceneBounds);

}  // namespace ht
