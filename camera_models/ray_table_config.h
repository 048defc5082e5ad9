// ray_table_config.h - the "rayTable" section of a display config (model "ray-table", docs/configs.md): where the
// per-pixel ray table of a calibrated display is stored. The table itself: ray_table.h.
#pragma once
#include <filesystem>

#include <nlohmann/json_fwd.hpp>

#include "camera_models/json_fields.h"

namespace ht {

// "rayTable": {"file": "table.exr", "units": 1.0}. The file path is resolved against the config file's directory.
struct RayTableConfig {
  std::filesystem::path file;  // the ray table (EXR, frame_io/ray_table_exr.h)
  double units = 1.0;          // world units per table unit (origins are scaled by it), > 0
};

// Parses and validates the section; `at` is its location ("rayTable"). Throws ConfigError.
RayTableConfig parseRayTable(const detail::JsonLocation& at, const nlohmann::json& section,
                             const std::filesystem::path& baseDir);

}  // namespace ht
