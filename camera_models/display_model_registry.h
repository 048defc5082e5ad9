// display_model_registry.h - one row per camera model: everything the config parser, the camera setup, the renderer
// and the frame packagers need to know about a model that is not in the model's own files. Adding a model is one row
// here plus its own files (docs/ARCHITECTURE.md, "Add a display model"); tests/camera_models/
// display_model_registry_test.cpp and tests/gpu/display_model_render_test.cpp walk every row through every stage.
#pragma once
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "camera_models/display_config.h"
#include "camera_models/frame_camera.h"
#include "camera_models/json_fields.h"
#include "camera_models/quilt_layout.h"
#include "common/bounds3.h"

namespace ht {

struct DisplayModelRow {
  DisplayModel model;     // == the row's index == its GPU model id (model_list.h)
  std::string_view name;  // the config's "model" value, also in errors and file metadata
  bool inConfigs;         // false: not a config "model" (the quilt cameras, CameraPath::Quilt of a lenticular)
  // The model's own config section (docs/configs.md), required for the model and rejected for every other; empty
  // when the model has none (lenticular reads "calibration", pinhole the shared "pinhole" preview section).
  std::string_view sectionKey;
  void (*parseSection)(const detail::JsonLocation& at, const nlohmann::json& section,
                       const std::filesystem::path& baseDir, DisplayConfig& config);  // null without a section
  bool (*hasSection)(const DisplayConfig& config);                                    // null without a section
  // Setup: the camera of a display of this model around the scene bounds (rayTable: the table read from the file
  // named by config.rayTable, ignored by the other models). Throws ConfigError for a config of another model.
  FrameCamera (*makeCamera)(const DisplayConfig& config, const Bounds3& sceneBounds,
                            std::shared_ptr<const RayTable> rayTable);
  FrameShape (*shape)(const FrameCamera& camera);                                 // what the camera renders
  void (*writeBlock)(const FrameCamera& camera, gpu_shared::CameraBlock& block);  // its GPU parameter block
  // The tile layout of the views when they form a quilt (quilt cameras, view grids), else nullopt.
  std::optional<QuiltLayout> (*viewQuilt)(const DisplayConfig& config, const FrameCamera& camera,
                                          const FrameShape& shape);
  std::string_view example;  // a small config of this model (JSON), parsed and rendered by the registry tests
};

// Every row, in model-id order.
std::span<const DisplayModelRow> displayModels();
const DisplayModelRow& displayModelRow(DisplayModel model);
// The row whose config name is `name` (rows with inConfigs only), or nullptr.
const DisplayModelRow* findConfigModel(std::string_view name);

}  // namespace ht
