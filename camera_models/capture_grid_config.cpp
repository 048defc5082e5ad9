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
  const glm::dvec2 spacing = detail::requireVector<2>(at, object, "spacing", expected);
  if (!(spacing.x > 0.0 && spacing.y > 0.0))
    detail::throwFieldError(at, "spacing", detail::findField(object, "spacing"), expected);
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
  const detail::ImageSize image = detail::requireImageSize(at, section, "image");
  c.imageWidth = image.width;
  c.imageHeight = image.height;
  return c;
}

}  // namespace ht
