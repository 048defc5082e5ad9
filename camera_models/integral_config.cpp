// integral_config.cpp - parsing and validation of the "integral" section (see integral_config.h).
#include "camera_models/integral_config.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace ht {

using detail::JsonLocation;
using nlohmann::json;

namespace {

constexpr long long kMaxPanelSize = 32768;

void rejectUnknown(const JsonLocation& at, const json& object, std::initializer_list<std::string_view> allowed) {
  for (const auto& [key, value] : object.items()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string list;
    for (std::string_view k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
    detail::throwFieldError(at, key, &value, "unknown key; expected one of: " + list);
  }
}

double requirePositive(const JsonLocation& at, const json& object, std::string_view key, const std::string& what) {
  const std::string expected = "expected a finite " + what + " > 0 (display units)";
  const double value = detail::requireNumber(at, object, key, false, expected);
  if (!(value > 0.0)) detail::throwFieldError(at, key, detail::findField(object, key), expected);
  return value;
}

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
  rejectUnknown(at, section, {"panelWidth", "panelHeight", "pixelPitch", "lensPitch", "lensOffset", "lensRotationDeg",
                              "gap", "focalLength", "viewerDistance", "frontPlane", "sampling"});
  IntegralConfig c;
  c.panelWidth = static_cast<std::uint32_t>(detail::requireInteger(at, section, "panelWidth", false, 1, kMaxPanelSize));
  c.panelHeight =
      static_cast<std::uint32_t>(detail::requireInteger(at, section, "panelHeight", false, 1, kMaxPanelSize));
  c.pixelPitch = requirePositive(at, section, "pixelPitch", "pixel pitch");
  c.lensPitch = requirePositive(at, section, "lensPitch", "lens pitch");
  c.lensOffset = readOffset(at, section);
  c.lensRotationDeg = detail::optionalNumber(at, section, "lensRotationDeg", false,
                                             "expected a finite angle in degrees").value_or(0.0);
  c.gap = requirePositive(at, section, "gap", "LCD-to-lens gap");
  c.focalLength = requirePositive(at, section, "focalLength", "lens focal length");
  c.viewerDistance = requirePositive(at, section, "viewerDistance", "viewer distance");
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
