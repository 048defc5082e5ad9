// quilt_setup.h - from a lenticular display config and a quilt layout to the quilt cameras: the GPU block
// (quilt_params.h, consumed by quilt_model.h) and a double-precision reference written independently of the float code.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/lenticular_reference.h"
#include "camera_models/quilt_layout.h"
#include "camera_models/quilt_params.h"
#include "scene/scene.h"

namespace ht {

// The display's cameras (resolveLenticularCamera: target, size, D, viewCone) with the quilt's render aspect and
// N = columns*rows views. Throws ConfigError if the config is not a lenticular display.
gpu_shared::QuiltParams makeQuiltParams(const DisplayConfig& config, const Bounds3& sceneBounds,
                                        const QuiltLayout& layout);

// docs/OPTICS.md §9 M1 in double: theta_i = viewCone*((i+0.5)/N - 0.5), o = target + (D tan(theta_i), 0, D),
// P = target + (((x+xi_x)/w - 0.5)*aspect*size, ((y+xi_y)/h - 0.5)*size, 0), d = normalize(P - o).
class QuiltReference {
 public:
  QuiltReference(const DisplayConfig& config, const Bounds3& sceneBounds, const QuiltLayout& layout);
  ReferenceRay ray(std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::dvec2 xi) const;
  const QuiltLayout& layout() const { return layout_; }

 private:
  LenticularCamera camera_;
  QuiltLayout layout_;
};

}  // namespace ht
