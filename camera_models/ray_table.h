// ray_table.h - a display calibrated per pixel (model "ray-table", docs/configs.md): one ray (origin, direction) per
// pixel, read from a file (frame_io/ray_table_exr.h; camera_models does not depend on an image library). The in-memory
// table with its validation, the GPU block (ray_table_params.h, consumed by
// ray_table_model.h) and a double-precision reference of the interpolation.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_reference.h"  // ReferenceRay
#include "camera_models/ray_table_config.h"
#include "camera_models/ray_table_params.h"
#include "common/bounds3.h"

namespace ht {

inline constexpr std::uint32_t kMaxRayTableSize = 16384;  // per side

// Throws ConfigError(source, "size", "WxH", ...) unless 1 <= width, height <= kMaxRayTableSize. Readers call it
// BEFORE allocating the table, so a corrupt header cannot request gigabytes.
void checkRayTableSize(std::uint64_t width, std::uint64_t height, const std::string& source);

struct RayTable {
  std::uint32_t width = 0, height = 0;
  std::vector<glm::vec3> origins;     // width*height, index y*width + x, y from the bottom; table units
  std::vector<glm::vec3> directions;  // same layout; non-zero (unit after normalizeDirections())

  std::size_t index(std::uint32_t x, std::uint32_t y) const { return std::size_t(y) * width + x; }

  // Throws ConfigError naming `source`, the entry and the value: size outside [1, 16384] per side, array sizes not
  // width*height, a non-finite origin or direction, a zero direction, or neighbouring directions (in a 2x2 cell) 90
  // degrees or more apart (their interpolation could pass through zero).
  void validate(const std::string& source) const;

  // Normalises (in double) every direction whose length is not 1 within 4e-7; unit ones are left bit-identical, so
  // the call is idempotent and a written-then-read table is unchanged.
  void normalizeDirections();
};

// World placement: o_w = target + units*o, d_w = d; target = camera.target, "auto" = bounds centre (origin if empty).
// Throws ConfigError if the config is not a ray-table display.
glm::dvec3 resolveRayTableTarget(const DisplayConfig& config, const Bounds3& sceneBounds);
gpu_shared::RayTableParams makeRayTableParams(const DisplayConfig& config, const RayTable& table,
                                              const Bounds3& sceneBounds);

// ray_table_model.h in double, written from its description (clamped bilinear interpolation, renormalised).
class RayTableReference {
 public:
  RayTableReference(const DisplayConfig& config, const RayTable& table, const Bounds3& sceneBounds);
  ReferenceRay ray(std::uint32_t x, std::uint32_t y, glm::dvec2 xi) const;  // world

 private:
  const RayTable* table_;
  double units_ = 1.0;
  glm::dvec3 target_{0.0};
};

}  // namespace ht
