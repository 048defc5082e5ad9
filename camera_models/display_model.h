// display_model.h - which camera model a display (or a frame) uses: one enum, numbered by model_ids.h, with one row
// each in the display-model registry (display_model_registry.h) that holds everything else about the model.
#pragma once
#include <cstdint>
#include <string_view>

#include "camera_models/model_ids.h"

namespace ht {

enum class DisplayModel : std::uint32_t {
  Lenticular = gpu_shared::HT_MODEL_LENTICULAR,
  Pinhole = gpu_shared::HT_MODEL_PINHOLE,
  Quilt = gpu_shared::HT_MODEL_QUILT,  // the quilt cameras of a lenticular display; no config has this model
  ProjectorArray = gpu_shared::HT_MODEL_PROJECTOR_ARRAY,
  Integral = gpu_shared::HT_MODEL_INTEGRAL,
  CaptureGrid = gpu_shared::HT_MODEL_CAPTURE_GRID,
  Oblique = gpu_shared::HT_MODEL_OBLIQUE,
  RayTable = gpu_shared::HT_MODEL_RAY_TABLE,
};

// The registry row's name: "lenticular", "pinhole", "quilt", "projector-array", ...
std::string_view displayModelName(DisplayModel model);

}  // namespace ht
