// display_camera.cpp - see display_camera.h.
#include "gpu/display_camera.h"

#include "camera_models/capture_grid_setup.h"
#include "camera_models/integral_setup.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/oblique_setup.h"
#include "camera_models/pinhole_params.h"
#include "camera_models/projector_setup.h"
#include "camera_models/quilt_setup.h"
#include "common/error.h"

namespace ht::gpu {
namespace {

FrameCamera rayTableCamera(const DisplayConfig& config, const Bounds3& bounds, std::shared_ptr<const RayTable> table) {
  if (!table) {
    throw ConfigError(config.sourcePath, "rayTable.file", "(not loaded)",
                      "a ray table read from the file before the camera is made (a caller bug)");
  }
  return RayTableCamera{makeRayTableParams(config, *table, bounds), std::move(table)};
}

FrameCamera nativeCamera(const DisplayConfig& config, const Bounds3& bounds, std::shared_ptr<const RayTable> table) {
  switch (config.model) {
    case DisplayModel::Oblique: return makeObliqueParams(config, bounds);
    case DisplayModel::RayTable: return rayTableCamera(config, bounds, std::move(table));
    case DisplayModel::Lenticular: return makeLenticularParams(config, bounds);
    case DisplayModel::Pinhole: return makePinholeParams(config, bounds);
    case DisplayModel::ProjectorArray: return makeProjectorArrayParams(config, bounds);
    case DisplayModel::Integral: return makeIntegralParams(config, bounds);
    case DisplayModel::CaptureGrid: return makeCaptureGridParams(config, bounds);
  }
  throw ConfigError(config.sourcePath, "model", std::string(displayModelName(config.model)),
                    "a model the renderer supports (docs/configs.md)");
}

// A view grid (capture grid, oblique directions) as a quilt: columns x rows tiles of the view size, view 0
// bottom-left. `grid`: x columns, y rows.
QuiltLayout viewGridQuilt(const FrameShape& shape, const glm::ivec4& grid) {
  const auto columns = static_cast<std::uint32_t>(grid.x), rows = static_cast<std::uint32_t>(grid.y);
  return makeQuiltLayout(columns, rows, columns * shape.width, rows * shape.height,
                         static_cast<double>(shape.width) / shape.height);
}

}  // namespace

DisplayCamera makeDisplayCamera(const DisplayConfig& config, const Bounds3& sceneBounds, CameraPath path,
                                std::shared_ptr<const RayTable> rayTable) {
  DisplayCamera result;
  if (path == CameraPath::Quilt) {
    if (config.model != DisplayModel::Lenticular) {
      throw ConfigError(config.sourcePath, "model", "\"" + std::string(displayModelName(config.model)) + "\"",
                        "\"lenticular\": only lenticular displays have quilt cameras (drop --quilt)");
    }
    const QuiltLayout layout = defaultQuiltLayout(config);
    result.camera = makeQuiltParams(config, sceneBounds, layout);
    result.quilt = layout;
  } else {
    result.camera = nativeCamera(config, sceneBounds, std::move(rayTable));
  }
  result.shape = frameShape(result.camera);
  if (const auto* grid = std::get_if<gpu_shared::CaptureGridParams>(&result.camera)) {
    result.quilt = viewGridQuilt(result.shape, grid->grid);
  }
  if (const auto* oblique = std::get_if<gpu_shared::ObliqueParams>(&result.camera)) {
    result.quilt = viewGridQuilt(result.shape, oblique->grid);
  }
  return result;
}

}  // namespace ht::gpu
