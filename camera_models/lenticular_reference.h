// lenticular_reference.h - double-precision oracle of the lenticular model, written independently of the shared
// float code in lenticular_model.h (tests, and benchmarks as the accuracy reference).
//
// Straight transcription of docs/OPTICS.md §9 M2: u = (x+0.5)/W, v = (y+0.5)/H (y from the bottom);
// classic phi = (u + c*subp + v*tilt)*pitch_s - center (holoplaycore.js GetSubpixelViews, §3.1);
// Gen3 phi = ((u + offX/W) + (v + offY/H)*tilt)*pitch_s - center (GetCellForPixel / GetPixelShift, §3.2);
// t = invView ? 1 - fract(phi) : fract(phi); flipSubp evaluates channel 2 - c; the footprint sample point moves by
// ((xi.x - 0.5)/(3W), (xi.y - 0.5)/H). Ray: looking-glass-webxr camera (§4.3): theta = viewCone*(t - 0.5),
// o = (D tan(theta), 0, D), P = ((u_s - 0.5)*aspect*size, (v_s - 0.5)*size, 0), d = normalize(P - o).
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "scene/scene.h"

namespace ht {

struct ReferenceRay {
  glm::dvec3 origin{0.0};
  glm::dvec3 dir{0.0};  // unit length
};

class LenticularReference {
 public:
  // Throws ConfigError if the config is not a lenticular display.
  LenticularReference(const DisplayConfig& config, const Bounds3& sceneBounds);

  std::uint32_t cell(std::uint32_t x, std::uint32_t y) const;  // Gen3 cell index (0 in the classic model)
  glm::dvec2 sampleUV(std::uint32_t x, std::uint32_t y, std::uint32_t c, glm::dvec2 xi) const;
  double viewPhase(std::uint32_t x, std::uint32_t y, std::uint32_t c, glm::dvec2 xi) const;  // t in [0, 1)
  ReferenceRay rayForPhase(double t, glm::dvec2 uv) const;
  ReferenceRay ray(std::uint32_t x, std::uint32_t y, std::uint32_t c, glm::dvec2 xi) const;

  const LenticularShaderValues& shaderValues() const { return shader_; }
  const LenticularCamera& camera() const { return camera_; }

 private:
  LookingGlassCalibration calibration_;
  LenticularShaderValues shader_;
  LenticularCamera camera_;
};

}  // namespace ht
