// display_camera.h - from a display config to the camera the renderer traces: the display's own model (native
// panel, projector images, LCD image, capture views), or for a lenticular display its quilt cameras (the vendor
// path, kept for comparison and for quilt capture).
#pragma once
#include <memory>
#include <optional>

#include "camera_models/display_config.h"
#include "camera_models/quilt_layout.h"
#include "common/bounds3.h"
#include "gpu/renderer.h"

namespace ht::gpu {

enum class CameraPath {
  Native,  // the display's model: per-subpixel rays (lenticular, integral), per-pixel rays of each view otherwise
  Quilt,   // lenticular displays only: the N sheared quilt cameras at the device's default quilt size
};

struct DisplayCamera {
  FrameCamera camera;
  FrameShape shape;
  // Tile layout of the views when they form a quilt: the quilt cameras (default device quilt) and capture grids
  // (columns x rows views, tiles of the image size); nullopt for single images and projector arrays.
  std::optional<QuiltLayout> quilt;
};

// Throws ConfigError when `path` is Quilt and the display is not lenticular, or when a ray-table display comes
// without its table (the caller reads the file named by config.rayTable: frame_io/ray_table_exr.h).
DisplayCamera makeDisplayCamera(const DisplayConfig& config, const Bounds3& sceneBounds,
                                CameraPath path = CameraPath::Native,
                                std::shared_ptr<const RayTable> rayTable = nullptr);

}  // namespace ht::gpu
