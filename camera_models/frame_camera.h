// frame_camera.h - the camera of a frame, what it renders, and its GPU block: the model-independent face of the
// display models. No Vulkan: the renderer (gpu/) takes a FrameCamera, and the CPU tests check shapes and blocks.
#pragma once
#include <cstdint>

#include "camera_models/model_list.h"

namespace ht {

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
