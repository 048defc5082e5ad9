// capture_grid_config.cpp - parsing and validation of the "captureGrid" section (see capture_grid_config.h).
#include "camera_models/capture_grid_config.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

namespace ht {

using detail::JsonLocation;
using nlohmann::json;

namespace {

glm::dvec2 readSpacing(const JsonLocation& at, const json& object) {
  const std::string expected = "expected [ds, dt] of finite numbers > 0 (world units)";
  const json* field = detail::findField(object, "spacing");
  if (field == nullptr || !field->is_array() || field->size() != 2)
    detail::throwFieldError(at, "spacing", field, expected);
  glm::dvec2 spacing;
  for (int i = 0; i < 2; ++i) {
    const json& c = (*field)[static_cast<std::size_t>(i)];
    if (!c.is_number() || !std::isfinite(c.get<double>()) || !(c.get<double>() > 0.0))
      detail::throwFieldError(at, "spacing", field, expected);
    spacing[i] = c.get<double>();
  }
  return spacing;
}

}  // namespace

CaptureGridConfig parseCaptureGrid(const JsonLocation& at, const json& section) {
  detail::rejectUnknownKeys(at, section, {"columns", "rows", "spacing", "distance", "window", "image"});
  CaptureGridConfig c;
  c.columns = static_cast<std::uint32_t>(detail::requireInteger(at, section, "columns", false, 1, 1024));
  c.rows = static_cast<std::uint32_t>(detail::requireInteger(at, section, "rows", false, 1, 1024));
  c.spacing = readSpacing(at, section);
  c.distance = detail::requirePositiveNumber(at, section, "distance", "expected a finite number > 0 (world units)");
  const json* window = detail::findField(section, "window");
  if (window == nullptr || !window->is_object())
    detail::throwFieldError(at, "window", window, "expected {\"width\": w, \"height\": h} (world units)");
  detail::rejectUnknownKeys(at.child("window"), *window, {"width", "height"});
  c.windowWidth =
      detail::requirePositiveNumber(at.child("window"), *window, "width", "expected a finite number > 0 (world units)");
  c.windowHeight = detail::requirePositiveNumber(at.child("window"), *window, "height",
                                                 "expected a finite number > 0 (world units)");
  const json* image = detail::findField(section, "image");
  if (image == nullptr || !image->is_object())
    detail::throwFieldError(at, "image", image, "expected {\"width\": W, \"height\": H} (pixels)");
  detail::rejectUnknownKeys(at.child("image"), *image, {"width", "height"});
  c.imageWidth =
      static_cast<std::uint32_t>(detail::requireInteger(at.child("image"), *image, "width", false, 1, 32768));
  c.imageHeight =
      static_cast<std::uint32_t>(detail::requireInteger(at.child("image"), *image, "height", false, 1, 32768));
  return c;
}

}  // namespace ht
