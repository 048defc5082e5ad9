// projector_array_config.h - the "projectorArray" section of a display config (model "projector-array",
// docs/configs.md): a HoloVizio-class horizontal-parallax-only (HPO) projector array (docs/OPTICS.md §6, §9 M3).
//
// Geometry is in display units (e.g. mm) in the display-local frame: screen = plane z = 0 centred on the origin,
// +x right, +y up, +z toward the viewer; projectors behind the screen (z < 0); observer line z = observerDistance,
// y = observerHeight. Field names follow wps1215/LightFieldDisplayModel UtilitiesBasic/HoloVizioModel.h
// (num_projectors, per-projector position, image size, screen size, observer_distance, angular_scattering).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "camera_models/json_fields.h"
#include "camera_models/lens_settings.h"

namespace ht {

// One projector: position and its pixel -> screen mapping.
struct ProjectorConfig {
  glm::dvec3 position{0.0};             // display units, z < 0
  std::uint32_t width = 0, height = 0;  // image size in pixels
  // Row-major 3x3 homography from pixel coordinates (px, py, 1) (py from the bottom, pixel centres at +0.5) to
  // homogeneous screen coordinates; nullopt = linear: the image fills the screen (docs/OPTICS.md §6, Doronin
  // RenderProjector: S = (-Sw/2 + Sw*px/W, -Sh/2 + Sh*py/H)).
  std::optional<std::array<double, 9>> homography;
};

struct ProjectorArrayConfig {
  double screenWidth = 0.0, screenHeight = 0.0;  // display units, > 0
  double observerDistance = 0.0;                 // z of the observer line, > 0
  double observerHeight = 0.0;                   // y of the observer line (tracked viewer height; 0 = screen centre)
  // Horizontal angular scattering of the screen (rad, >= 0); nullopt = "auto": 1.5 x the angle between the two
  // central projectors seen from the screen centre (LightFieldDisplayModel GenerateSampleModels/main.cpp).
  std::optional<double> angularScattering;
  std::vector<ProjectorConfig> projectors;  // [1, HT_MAX_PROJECTORS]
  // "lens": the projectors' lens, all alike (a wall of one projector model): focal length (px), principal point
  // offset from the image centre (px) and Brown-Conrady distortion; nullopt = ideal lenses.
  struct Lens {
    double focalLengthPx = 0.0;
    glm::dvec2 principalOffsetPx{0.0};
    LensDistortionSettings distortion;
  };
  std::optional<Lens> lens;
};

// Parses and validates the section; `at` is its location ("projectorArray"). Throws ConfigError.
ProjectorArrayConfig parseProjectorArray(const detail::JsonLocation& at, const nlohmann::json& section);

// Row-major homography of the linear mapping of a W x H image onto a Sw x Sh screen centred on the origin.
std::array<double, 9> linearProjectorMapping(double screenWidth, double screenHeight, std::uint32_t width,
                                             std::uint32_t height);

}  // namespace ht
