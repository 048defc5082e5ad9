// model_list.h - the one list of camera models, for C++ and GLSL: each model's number, its GPU parameter block and
// (C++ only) its DisplayModel value and FrameCamera alternative. A new model adds one line to each list here, one row
// to the display-model registry (display_model_registry.cpp) and its own files (docs/ARCHITECTURE.md §4.1).
//
// The number is the model's row in the registry, its DisplayModel value, its FrameCamera alternative and the MODEL
// specialisation constant of the raygen / resolve / refine_select kernels. GLSL sees no C++ enum, so the numbers are
// constants here and DisplayModel takes its values from them.
#ifndef HT_MODEL_LIST_H
#define HT_MODEL_LIST_H
#include "common/glsl_cpp.h"
#include "camera_models/camera_params.h"
#include "camera_models/capture_grid_params.h"
#include "camera_models/integral_params.h"
#include "camera_models/oblique_params.h"
#include "camera_models/projector_params.h"
#include "camera_models/quilt_params.h"
#include "camera_models/ray_table_params.h"

HT_SHARED_BEGIN

// Subpixel models (lenticular, integral) trace each R, G, B subpixel with its own rays and keep one channel per
// target; the others trace RGB pixels of `views` images.
HT_CONST uint HT_MODEL_LENTICULAR = 0u;
HT_CONST uint HT_MODEL_PINHOLE = 1u;
HT_CONST uint HT_MODEL_QUILT = 2u;  // a lenticular display's quilt cameras (not a config "model")
HT_CONST uint HT_MODEL_PROJECTOR_ARRAY = 3u;
HT_CONST uint HT_MODEL_INTEGRAL = 4u;
HT_CONST uint HT_MODEL_CAPTURE_GRID = 5u;
HT_CONST uint HT_MODEL_OBLIQUE = 6u;
HT_CONST uint HT_MODEL_RAY_TABLE = 7u;
HT_CONST uint HT_MODEL_COUNT = 8u;

HT_INLINE bool ht_model_has_subpixel_targets(uint model) {
  return model == HT_MODEL_LENTICULAR || model == HT_MODEL_INTEGRAL;
}

// The camera parameters of a frame as the kernels read them (member `camera` of the FrameBlock uniform,
// gpu/wavefront_types.h): a frame fills its own model's block (registry row writeBlock) and leaves the others zero.
// Every member is a 16-byte multiple of vec4/ivec4/mat4, so std140 and C++ agree on the layout.
struct CameraBlock {
  LenticularParams lenticular;
  PinholeParams pinhole;
  QuiltParams quilt;
  IntegralParams integral;
  CaptureGridParams captureGrid;
  ObliqueParams oblique;
  RayTableParams rayTable;
  ProjectorArrayParams projectors;
};

HT_SHARED_END

#ifndef HT_GLSL
#include <cstdint>
#include <memory>
#include <string_view>
#include <variant>

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

struct RayTable;

// A per-pixel ray table and its placement; the renderer uploads the table once per table object (shared_ptr
// identity).
struct RayTableCamera {
  gpu_shared::RayTableParams params{};
  std::shared_ptr<const RayTable> table;
};

// The camera of a frame: alternative i is the parameter block of model i.
using FrameCamera = std::variant<gpu_shared::LenticularParams, gpu_shared::PinholeParams, gpu_shared::QuiltParams,
                                 gpu_shared::ProjectorArrayParams, gpu_shared::IntegralParams,
                                 gpu_shared::CaptureGridParams, gpu_shared::ObliqueParams, RayTableCamera>;
static_assert(std::variant_size_v<FrameCamera> == gpu_shared::HT_MODEL_COUNT, "one FrameCamera alternative per model");

}  // namespace ht
#endif  // HT_GLSL

#endif  // HT_MODEL_LIST_H
