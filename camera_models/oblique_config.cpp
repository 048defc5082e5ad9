// oblique_config.cpp - parsing and validation of the "oblique" section (see oblique_config.h).
#include "camera_models/oblique_config.h"

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

namespace ht {

using detail::JsonLocation;
using nlohmann::json;

namespace {

bool isAuto(const json& value) { return value.is_string() && value.get<std::string>() == "auto"; }

// A full cone in degrees, [0, 180): the outermost view is at +-cone/2*(1 - 1/n) < 90 degrees, so tan() is finite.
double readCone(const JsonLocation& at, const json& section, std::string_view key) {
  const std::string expected = "expected a full angular range in degrees in [0, 180) (0 = no parallax on this axis)";
  const double value = detail::requireNumber(at, section, key, false, expected);
  if (!(value >= 0.0 && value < 180.0)) detail::throwFieldError(at, key, detail::findField(section, key), expected);
  return value;
}

}  // namespace

ObliqueConfig parseOblique(const JsonLocation& at, const json& section) {
  detail::rejectUnknownKeys(at, section,
                            {"columns", "rows", "horizontalConeDeg", "verticalConeDeg", "image", "window", "zFront"});
  ObliqueConfig c;
  c.columns = static_cast<std::uint32_t>(detail::requireInteger(at, section, "columns", false, 1, 1024));
  c.rows = static_cast<std::uint32_t>(detail::requireInteger(at, section, "rows", false, 1, 1024));
  c.horizontalConeDeg = readCone(at, section, "horizontalConeDeg");
  c.verticalConeDeg = detail::findField(section, "verticalConeDeg") != nullptr || c.rows > 1
                          ? readCone(at, section, "verticalConeDeg")
                          : 0.0;
  const json* image = detail::findField(section, "image");
  if (image == nullptr || !image->is_object())
    detail::throwFieldError(at, "image", image, "expected {\"width\": W, \"height\": H} (pixels)");
  detail::rejectUnknownKeys(at.child("image"), *image, {"width", "height"});
  c.imageWidth =
      static_cast<std::uint32_t>(detail::requireInteger(at.child("image"), *image, "width", false, 1, 32768));
  c.imageHeight =
      static_cast<std::uint32_t>(detail::requireInteger(at.child("image"), *image, "height", false, 1, 32768));
  const json* window = detail::findField(section, "window");
  if (window != nullptr && !isAuto(*window)) {
    if (!window->is_object())
      detail::throwFieldError(at, "window", window,
                              "expected {\"width\": w, \"height\": h} (world units) or \"auto\" (from camera.size)");
    detail::rejectUnknownKeys(at.child("window"), *window, {"width", "height"});
    const std::string expected = "expected a finite number > 0 (world units)";
    c.windowWidth = detail::requirePositiveNumber(at.child("window"), *window, "width", expected);
    c.windowHeight = detail::requirePositiveNumber(at.child("window"), *window, "height", expected);
  }
  const json* zFront = detail::findField(section, "zFront");
  if (zFront != nullptr && !isAuto(*zFront))
    c.zFront = detail::requirePositiveNumber(
        at, section, "zFront", "expected a distance > 0 in front of the window (world units) or \"auto\"");
  return c;
}

}  // namespace ht
