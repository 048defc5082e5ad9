// integral_config.cpp - parsing and validation of the "integral" section (see integral_config.h).
#include "camera_models/integral_config.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

namespace ht {

using detail::JsonLocation;
using nlohmann::json;

namespace {

constexpr long long kMaxPanelSize = 32768;

glm::dvec2 readOffset(const JsonLocation& at, const json& object) {
  const json* field = detail::findField(object, "lensOffset");
  if (field == nullptr) return glm::dvec2(0.0);
  const std::string expected = "expected [x, y] of finite numbers (display units)";
  if (!field->is_array() || field->size() != 2) detail::throwFieldError(at, "lensOffset", field, expected);
  glm::dvec2 offset;
  for (int i = 0; i < 2; ++i) {
    const json& c = (*field)[static_cast<std::size_t>(i)];
    if (!c.is_number() || !std::isfinite(c.get<double>())) detail::throwFieldError(at, "lensOffset", field, expected);
    offset[i] = c.get<double>();
  }
  return offset;
}

LensSampling readSampling(const JsonLocation& at, const json& object) {
  const json* field = detail::findField(object, "sampling");
  if (field == nullptr) return LensSampling::Centre;
  if (field->is_string() && field->get<std::string>() == "centre") return LensSampling::Centre;
  if (field->is_string() && field->get<std::string>() == "aperture") return LensSampling::Aperture;
  detail::throwFieldError(at, "sampling", field, "expected \"centre\" or \"aperture\"");
}

}  // namespace

IntegralConfig parseIntegral(const JsonLocation& at, const json& section) {
  detail::rejectUnknownKeys(at, section,
                            {"panelWidth", "panelHeight", "pixelPitch", "lensPitch", "lensOffset", "lensRotationDeg",
                             "gap", "focalLength", "viewerDistance", "frontPlane", "sampling"});
  IntegralConfig c;
  c.panelWidth = static_cast<std::uint32_t>(detail::requireInteger(at, section, "panelWidth", false, 1, kMaxPanelSize));
  c.panelHeight =
      static_cast<std::uint32_t>(detail::requireInteger(at, section, "panelHeight", false, 1, kMaxPanelSize));
  c.pixelPitch =
      detail::requirePositiveNumber(at, section, "pixelPitch", "expected a finite pixel pitch > 0 (display units)");
  c.lensPitch =
      detail::requirePositiveNumber(at, section, "lensPitch", "expected a finite lens pitch > 0 (display units)");
  c.lensOffset = readOffset(at, section);
  c.lensRotationDeg =
      detail::optionalNumber(at, section, "lensRotationDeg", false, "expected a finite angle in degrees").value_or(0.0);
  c.gap = detail::requirePositiveNumber(at, section, "gap", "expected a finite LCD-to-lens gap > 0 (display units)");
  c.focalLength = detail::requirePositiveNumber(at, section, "focalLength",
                                                "expected a finite lens focal length > 0 (display units)");
  c.viewerDistance = detail::requirePositiveNumber(at, section, "viewerDistance",
                                                   "expected a finite viewer distance > 0 (display units)");
  c.frontPlane = c.viewerDistance;
  if (detail::findField(section, "frontPlane") != nullptr) {
    const std::string expected = "expected a finite distance in (0, viewerDistance] (display units)";
    c.frontPlane = detail::requireNumber(at, section, "frontPlane", false, expected);
    if (!(c.frontPlane > 0.0 && c.frontPlane <= c.viewerDistance))
      detail::throwFieldError(at, "frontPlane", detail::findField(section, "frontPlane"), expected);
  }
  c.sampling = readSampling(at, section);
  return c;
}

}  // namespace ht
