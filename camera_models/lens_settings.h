// lens_settings.h - Brown-Conrady lens coefficients as a display config gives them ("distortion" objects of the
// "pinhole" and "projectorArray.lens" sections, docs/configs.md); formulas in lens_distortion.h.
#pragma once
#include <nlohmann/json_fwd.hpp>

#include "camera_models/json_fields.h"

namespace ht {

// OpenCV's convention, on normalized image coordinates (X/Z, Y/Z). All zero = an ideal lens.
struct LensDistortionSettings {
  double k1 = 0.0, k2 = 0.0, k3 = 0.0, p1 = 0.0, p2 = 0.0;
  bool any() const { return k1 != 0.0 || k2 != 0.0 || k3 != 0.0 || p1 != 0.0 || p2 != 0.0; }
};

// {"k1", "k2", "k3", "p1", "p2"}, each a finite number, default 0; unknown keys refused. `at` = the object's location.
LensDistortionSettings parseLensDistortion(const detail::JsonLocation& at, const nlohmann::json& distortion);

}  // namespace ht
