// frame_camera.h - the camera of a frame, what it renders, and its GPU block: the model-independent face of the
// display models. No Vulkan: the renderer (gpu/) takes a FrameCamera, and the CPU tests check shapes and blocks.
#pragma once
#include <cstdint>
#include <memory>
#include <variant>

#include "camera_models/camera_block.h"
#include "camera_models/display_model.h"

namespace ht {

struct RayTable;

// A per-pixel ray table and its placement; the renderer uploads the table once per table object (shared_ptr
// identity).
struct RayTableCamera {
  gpu_shared::RayTableParams params{};
  std::shared_ptr<const RayTable> table;
};

// The camera of a frame: alternative i is the parameter block of model i (DisplayModel, model_ids.h).
using FrameCamera = std::variant<gpu_shared::LenticularParams, gpu_shared::PinholeParams, gpu_shared::QuiltParams,
                                 gpu_shared::ProjectorArrayParams, gpu_shared::IntegralParams,
                                 gpu_shared::CaptureGridParams, gpu_shared::ObliqueParams, RayTableCamera>;
static_assert(std::variant_size_v<FrameCamera> == gpu_shared::HT_MODEL_COUNT, "one FrameCamera alternative per model");

inline DisplayModel cameraModel(const FrameCamera& camera) { return static_cast<DisplayModel>(camera.index()); }

// What a camera renders: `views` images of width x height pixels; subpixel models trace 3 targets per pixel.
struct FrameShape {
  std::uint32_t model = 0;  // gpu_shared::HT_MODEL_*, the kernels' MODEL specialisation
  std::uint32_t width = 0, height = 0, views = 1;
  std::uint32_t targetsPerPixel = 1;
  std::uint64_t targets() const { return static_cast<std::uint64_t>(width) * height * views * targetsPerPixel; }
};

// Through the camera's registry row. Throws GpuError for a camera the GPU cannot render (more projectors than
// HT_MAX_PROJECTORS, a ray-table camera without its table).
FrameShape frameShape(const FrameCamera& camera);

// The GPU block of the camera: the block of its model filled, every other byte zero.
gpu_shared::CameraBlock cameraBlock(const FrameCamera& camera);

}  // namespace ht
