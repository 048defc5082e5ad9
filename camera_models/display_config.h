// display_config.h - holotrace's one display-config format (docs/configs.md): which camera model, the display
// calibration, where the display sits in the scene, and default sampling.
//
// loadDisplayConfig() also accepts a raw Looking Glass visual.json unchanged (detected by a top-level "pitch" or
// "slope"), which is then a lenticular display with default camera placement. Unknown keys in OUR format are errors
// (a typo must not pass silently); unknown keys inside a visual.json are kept.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "camera_models/capture_grid_config.h"
#include "camera_models/integral_config.h"
#include "camera_models/lens_settings.h"
#include "camera_models/looking_glass_calibration.h"
#include "camera_models/model_list.h"
#include "camera_models/oblique_config.h"
#include "camera_models/panel_placement.h"
#include "camera_models/projector_array_config.h"
#include "camera_models/ray_table_config.h"

namespace ht {

// A quilt size chosen in the config instead of the device default (quilt_layout.h defaultQuiltLayout): `columns` x
// `rows` views tiled into a `width` x `height` quilt, e.g. a small quilt for tests or a 2x-pixel one for quality.
struct QuiltSize {
  std::uint32_t columns = 0, rows = 0;
  std::uint32_t width = 0, height = 0;
};

// Where the display's focal rectangle sits in the scene (looking-glass-webxr camera, docs/OPTICS.md §4.3).
// The display-local frame has its origin at `target` and world-aligned axes (+z toward the viewer).
struct CameraPlacement {
  std::optional<glm::dvec3> target;  // world position of the focal-rectangle centre; nullopt = "auto" (bounds centre)
  std::optional<double> size;        // focal-rectangle height (webxr targetDiam), world units; nullopt = "auto"
  double fovyDeg = 14.0;             // vertical fov of the quilt cameras (looking-glass-webxr default), (0, 180)
  double depthiness = 1.0;           // multiplies viewCone (webxr uses 1.25 by default; we default to 1.0)
  std::optional<QuiltSize> quilt;    // "quilt": {"columns", "rows", "width", "height"}; nullopt = device default
};

// Pinhole camera (model "pinhole", docs/OPTICS.md §9 M0); also the preview camera of a lenticular display.
struct PinholeSettings {
  std::optional<std::uint32_t> width, height;  // image size in pixels; nullopt = panel size or 1280x720
  std::optional<double> fovyDeg;               // vertical fov in degrees; nullopt = camera.fovyDeg (lenticular) or 45
  std::optional<glm::dvec3> eye;               // nullopt = "auto"
  std::optional<glm::dvec3> lookAt;            // nullopt = "auto" (target / bounds centre)
  glm::dvec3 up{0.0, 1.0, 0.0};
  LensDistortionSettings distortion;  // "distortion": {"k1", "k2", "k3", "p1", "p2"}, each default 0
};

struct DisplayConfig {
  std::string name;
  std::string description;
  std::string sourcePath;                              // file path, or "builtin:NAME"
  DisplayModel model = DisplayModel::Lenticular;       // a registry row with inConfigs (display_model_registry.h)
  std::optional<LookingGlassCalibration> calibration;  // required for (and only for) the lenticular model
  CameraPlacement camera;
  std::uint32_t spp = 4;  // default samples per subpixel / pixel, [1, 4096]
  // Stop rule of progressive streams on this display (docs/REUSE.md §2, docs/SERVICE.md §4.1), "progressive":
  // {"target_error", "max_spp"}; unset = the daemon's default. A request's values come first.
  std::optional<double> progressiveTargetError;
  std::optional<std::uint32_t> progressiveMaxSpp;
  PinholeSettings pinhole;
  std::optional<ProjectorArrayConfig> projectorArray;  // required for (and only for) model "projector-array"
  std::optional<IntegralConfig> integral;              // required for (and only for) model "integral"
  std::optional<CaptureGridConfig> captureGrid;        // required for (and only for) model "capture-grid"
  std::optional<ObliqueConfig> oblique;                // required for (and only for) model "oblique"
  std::optional<RayTableConfig> rayTable;              // required for (and only for) model "ray-table"
  PanelPlacement panel;  // "panel": {"output"} or {"geometry"}: the panel's monitor (lenticular only; optional)
};

// Reads our format or a raw visual.json from disk. Throws ConfigError.
DisplayConfig loadDisplayConfig(const std::filesystem::path& file);

// Parses JSON text; `sourceName` names the source in errors, relative calibration paths resolve against `baseDir`.
DisplayConfig parseDisplayConfig(std::string_view json, const std::string& sourceName,
                                 const std::filesystem::path& baseDir);

// The configs shipped in configs/*.json, embedded at build time (no files needed at run time).
DisplayConfig builtinDisplay(std::string_view name);
std::vector<std::string> builtinDisplayNames();

// "builtin:NAME" or a file path.
DisplayConfig resolveDisplay(const std::string& spec);

}  // namespace ht
