// display_camera.cpp - see display_camera.h. Everything model-specific comes from the model's registry row.
#include "gpu/display_camera.h"

#include "camera_models/display_model_registry.h"
#include "common/error.h"

namespace ht::gpu {

DisplayCamera makeDisplayCamera(const DisplayConfig& config, const Bounds3& sceneBounds, CameraPath path,
                                std::shared_ptr<const RayTable> rayTable) {
  if (path == CameraPath::Quilt && config.model != DisplayModel::Lenticular) {
    throw ConfigError(config.sourcePath, "model", "\"" + std::string(displayModelName(config.model)) + "\"",
                      "\"lenticular\": only lenticular displays have quilt cameras (drop --quilt)");
  }
  const DisplayModelRow& row = displayModelRow(path == CameraPath::Quilt ? DisplayModel::Quilt : config.model);
  DisplayCamera result;
  result.camera = row.makeCamera(config, sceneBounds, std::move(rayTable));
  result.shape = row.shape(result.camera);
  result.quilt = row.viewQuilt(config, result.camera, result.shape);
  return result;
}

}  // namespace ht::gpu
