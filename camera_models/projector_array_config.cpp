// projector_array_config.cpp - parsing and validation of the "projectorArray" section (see projector_array_config.h).
#include "camera_models/projector_array_config.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "camera_models/projector_params.h"

namespace ht {

using detail::JsonLocation;
using nlohmann::json;

namespace {

constexpr long long kMaxImageSize = 32768;

// [x, y, z], finite, z < 0: projectors sit behind the screen (docs/OPTICS.md §9 M3, P_k.z < 0).
glm::dvec3 readPosition(const JsonLocation& at, const json& object) {
  const std::string expected = "expected [x, y, z] of finite numbers (display units) with z < 0 (behind the screen)";
  const json* field = detail::findField(object, "position");
  if (field == nullptr || !field->is_array() || field->size() != 3)
    detail::throwFieldError(at, "position", field, expected);
  glm::dvec3 p;
  for (int i = 0; i < 3; ++i) {
    const json& c = (*field)[static_cast<std::size_t>(i)];
    if (!c.is_number() || !std::isfinite(c.get<double>())) detail::throwFieldError(at, "position", field, expected);
    p[i] = c.get<double>();
  }
  if (!(p.z < 0.0)) detail::throwFieldError(at, "position", field, expected);
  return p;
}

// 3x3 row-major, finite, mapping every image corner to a finite point (w > 0 there, so the image does not wrap through
// infinity).
std::array<double, 9> readHomography(const JsonLocation& at, const json& object, std::uint32_t width,
                                     std::uint32_t height) {
  const std::string expected =
      "expected [[h00, h01, h02], [h10, h11, h12], [h20, h21, h22]] of finite numbers with h20*x + h21*y + h22 > 0 "
      "at every image corner";
  const json* field = detail::findField(object, "homography");
  if (field == nullptr || !field->is_array() || field->size() != 3)
    detail::throwFieldError(at, "homography", field, expected);
  std::array<double, 9> h{};
  for (std::size_t r = 0; r < 3; ++r) {
    const json& row = (*field)[r];
    if (!row.is_array() || row.size() != 3) detail::throwFieldError(at, "homography", field, expected);
    for (std::size_t c = 0; c < 3; ++c) {
      if (!row[c].is_number() || !std::isfinite(row[c].get<double>()))
        detail::throwFieldError(at, "homography", field, expected);
      h[r * 3 + c] = row[c].get<double>();
    }
  }
  for (double x : {0.0, double(width)})
    for (double y : {0.0, double(height)})
      if (!(h[6] * x + h[7] * y + h[8] > 0.0)) detail::throwFieldError(at, "homography", field, expected);
  const double det =
      h[0] * (h[4] * h[8] - h[5] * h[7]) - h[1] * (h[3] * h[8] - h[5] * h[6]) + h[2] * (h[3] * h[7] - h[4] * h[6]);
  if (!(std::fabs(det) > 0.0)) detail::throwFieldError(at, "homography", field, expected + " (non-singular)");
  return h;
}

ProjectorConfig readProjector(const JsonLocation& at, const json& object, std::optional<std::uint32_t> defaultWidth,
                              std::optional<std::uint32_t> defaultHeight) {
  if (!object.is_object()) detail::throwFieldError(at, "", &object, "expected a projector object");
  detail::rejectUnknownKeys(at, object, {"position", "width", "height", "homography"});
  ProjectorConfig projector;
  projector.position = readPosition(at, object);
  auto width = detail::optionalInteger(at, object, "width", false, 1, kMaxImageSize);
  auto height = detail::optionalInteger(at, object, "height", false, 1, kMaxImageSize);
  if (!width && !defaultWidth)
    detail::throwFieldError(at, "width", nullptr, "expected an integer in [1, 32768] here or in \"image\"");
  if (!height && !defaultHeight)
    detail::throwFieldError(at, "height", nullptr, "expected an integer in [1, 32768] here or in \"image\"");
  projector.width = width ? static_cast<std::uint32_t>(*width) : *defaultWidth;
  projector.height = height ? static_cast<std::uint32_t>(*height) : *defaultHeight;
  if (detail::findField(object, "homography") != nullptr)
    projector.homography = readHomography(at, object, projector.width, projector.height);
  return projector;
}

// {"focalLength": f (px, > 0), "principalOffset": [dx, dy] (px, default [0, 0]), "distortion": {...}}.
ProjectorArrayConfig::Lens readLens(const JsonLocation& at, const json* lens) {
  if (!lens->is_object())
    detail::throwFieldError(at, "", lens,
                            "expected {\"focalLength\": f, \"principalOffset\": [dx, dy], \"distortion\": {...}}");
  detail::rejectUnknownKeys(at, *lens, {"focalLength", "principalOffset", "distortion"});
  ProjectorArrayConfig::Lens out;
  out.focalLengthPx = detail::requirePositiveNumber(at, *lens, "focalLength",
                                                    "expected the lens focal length in pixels, a finite number > 0");
  if (const json* offset = detail::findField(*lens, "principalOffset")) {
    const std::string expected = "expected [dx, dy] (pixels from the image centre), finite";
    if (!offset->is_array() || offset->size() != 2) detail::throwFieldError(at, "principalOffset", offset, expected);
    for (std::size_t i = 0; i < 2; ++i) {
      const json& v = (*offset)[i];
      if (!v.is_number() || !std::isfinite(v.get<double>()))
        detail::throwFieldError(at, "principalOffset", offset, expected);
      out.principalOffsetPx[static_cast<int>(i)] = v.get<double>();
    }
  }
  if (const json* distortion = detail::findField(*lens, "distortion")) {
    if (!distortion->is_object()) detail::throwFieldError(at, "distortion", distortion, "expected a JSON object");
    out.distortion = parseLensDistortion(at.child("distortion"), *distortion);
  }
  return out;
}

}  // namespace

std::array<double, 9> linearProjectorMapping(double screenWidth, double screenHeight, std::uint32_t width,
                                             std::uint32_t height) {
  // Doronin RenderProjector (docs/OPTICS.md §6): S = (-Sw/2 + Sw*(i+0.5)/W, -Sh/2 + Sh*(j+0.5)/H) with j from the
  // bottom; (i+0.5, j+0.5) is the pixel position here, so the matrix acts on (px, py, 1).
  return {screenWidth / width, 0.0, -0.5 * screenWidth, 0.0, screenHeight / height, -0.5 * screenHeight, 0.0, 0.0, 1.0};
}

ProjectorArrayConfig parseProjectorArray(const JsonLocation& at, const json& section) {
  detail::rejectUnknownKeys(
      at, section,
      {"screen", "observerDistance", "observerHeight", "angularScattering", "image", "projectors", "lens"});
  ProjectorArrayConfig config;
  const json* screen = detail::findField(section, "screen");
  if (screen == nullptr || !screen->is_object())
    detail::throwFieldError(at, "screen", screen, "expected {\"width\": w, \"height\": h} (display units)");
  const JsonLocation screenAt = at.child("screen");
  detail::rejectUnknownKeys(screenAt, *screen, {"width", "height"});
  config.screenWidth =
      detail::requirePositiveNumber(screenAt, *screen, "width", "expected a finite screen width (display units) > 0");
  config.screenHeight =
      detail::requirePositiveNumber(screenAt, *screen, "height", "expected a finite screen height (display units) > 0");
  config.observerDistance = detail::requirePositiveNumber(at, section, "observerDistance",
                                                          "expected a finite observer distance (display units) > 0");
  config.observerHeight =
      detail::optionalNumber(at, section, "observerHeight", false, "expected a finite height (display units)")
          .value_or(0.0);
  const json* scattering = detail::findField(section, "angularScattering");
  if (scattering != nullptr && !(scattering->is_string() && scattering->get<std::string>() == "auto")) {
    const std::string expected = "expected a finite angle >= 0 (radians) or \"auto\"";
    const double value = detail::requireNumber(at, section, "angularScattering", false, expected);
    if (!(value >= 0.0)) detail::throwFieldError(at, "angularScattering", scattering, expected);
    config.angularScattering = value;
  }

  std::optional<std::uint32_t> defaultWidth, defaultHeight;
  if (const json* image = detail::findField(section, "image")) {
    if (!image->is_object()) detail::throwFieldError(at, "image", image, "expected {\"width\": W, \"height\": H}");
    const JsonLocation imageAt = at.child("image");
    detail::rejectUnknownKeys(imageAt, *image, {"width", "height"});
    defaultWidth =
        static_cast<std::uint32_t>(detail::requireInteger(imageAt, *image, "width", false, 1, kMaxImageSize));
    defaultHeight =
        static_cast<std::uint32_t>(detail::requireInteger(imageAt, *image, "height", false, 1, kMaxImageSize));
  }
  const json* projectors = detail::findField(section, "projectors");
  const std::string countExpected =
      "expected an array of 1 to " + std::to_string(gpu_shared::HT_MAX_PROJECTORS) + " projector objects";
  if (projectors == nullptr || !projectors->is_array() || projectors->empty() ||
      projectors->size() > gpu_shared::HT_MAX_PROJECTORS)
    detail::throwFieldError(at, "projectors", projectors, countExpected);
  for (std::size_t k = 0; k < projectors->size(); ++k) {
    const JsonLocation projectorAt = at.child("projectors[" + std::to_string(k) + "]");
    config.projectors.push_back(readProjector(projectorAt, (*projectors)[k], defaultWidth, defaultHeight));
  }
  if (const json* lens = detail::findField(section, "lens")) config.lens = readLens(at.child("lens"), lens);
  return config;
}

}  // namespace ht
