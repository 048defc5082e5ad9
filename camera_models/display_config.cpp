// display_config.cpp - parsing and validation of holotrace display configs (docs/configs.md).
#include "camera_models/display_config.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include <nlohmann/json.hpp>

#include "camera_models/display_model_registry.h"
#include "camera_models/embedded_display_configs.h"
#include "camera_models/json_fields.h"
#include "common/error.h"

namespace ht {

using detail::JsonLocation;
using nlohmann::json;

namespace {

constexpr long long kMaxSpp = 4096;

// Our format is strict: every key must be known (detail::rejectUnknownKeys), so a typo is reported, not ignored.

const json& requireObject(const JsonLocation& at, const json& parent, std::string_view key) {
  const json* field = detail::findField(parent, key);
  if (field == nullptr || !field->is_object()) detail::throwFieldError(at, key, field, "expected a JSON object");
  return *field;
}

// [x, y, z] of finite numbers, or "auto" (nullopt) when allowed.
std::optional<glm::dvec3> readPoint(const JsonLocation& at, const json& object, std::string_view key, bool allowAuto) {
  const std::string expected = std::string("expected [x, y, z] of finite numbers") + (allowAuto ? " or \"auto\"" : "");
  return detail::optionalVector<3>(at, object, key, expected, allowAuto);
}

double readAngle(const JsonLocation& at, const json& object, std::string_view key, double fallback) {
  const std::string expected = "expected a field of view in degrees in (0, 180)";
  double value = detail::optionalNumber(at, object, key, false, expected).value_or(fallback);
  if (!(value > 0.0 && value < 180.0)) detail::throwFieldError(at, key, detail::findField(object, key), expected);
  return value;
}

QuiltSize readQuiltSize(const JsonLocation& at, const json& quilt) {
  detail::rejectUnknownKeys(at, quilt, {"columns", "rows", "width", "height"});
  QuiltSize size;
  size.columns = static_cast<std::uint32_t>(detail::requireInteger(at, quilt, "columns", false, 1, 1024));
  size.rows = static_cast<std::uint32_t>(detail::requireInteger(at, quilt, "rows", false, 1, 1024));
  size.width =
      static_cast<std::uint32_t>(detail::requireInteger(at, quilt, "width", false, size.columns, kMaxImageSide));
  size.height =
      static_cast<std::uint32_t>(detail::requireInteger(at, quilt, "height", false, size.rows, kMaxImageSide));
  return size;
}

CameraPlacement readCamera(const JsonLocation& at, const json& camera) {
  detail::rejectUnknownKeys(at, camera, {"target", "size", "fovyDeg", "depthiness", "quilt"});
  CameraPlacement placement;
  placement.target = readPoint(at, camera, "target", true);
  const json* size = detail::findField(camera, "size");
  if (size != nullptr && !detail::isAuto(*size)) {
    const std::string expected = "expected a focal-rectangle height > 0 (world units) or \"auto\"";
    double value = detail::requireNumber(at, camera, "size", false, expected);
    if (!(value > 0.0)) detail::throwFieldError(at, "size", size, expected);
    placement.size = value;
  }
  placement.fovyDeg = readAngle(at, camera, "fovyDeg", placement.fovyDeg);
  const std::string depthExpected = "expected a finite number > 0 (multiplies viewCone)";
  placement.depthiness =
      detail::optionalNumber(at, camera, "depthiness", false, depthExpected).value_or(placement.depthiness);
  if (!(placement.depthiness > 0.0))
    detail::throwFieldError(at, "depthiness", detail::findField(camera, "depthiness"), depthExpected);
  if (const json* quilt = detail::findField(camera, "quilt")) {
    if (!quilt->is_object())
      detail::throwFieldError(at, "quilt", quilt, "expected {\"columns\", \"rows\", \"width\", \"height\"}");
    placement.quilt = readQuiltSize(at.child("quilt"), *quilt);
  }
  return placement;
}

PinholeSettings readPinhole(const JsonLocation& at, const json& pinhole) {
  detail::rejectUnknownKeys(at, pinhole, {"width", "height", "fovyDeg", "eye", "lookAt", "up", "distortion"});
  PinholeSettings settings;
  settings.width = detail::optionalImageSide(at, pinhole, "width");
  settings.height = detail::optionalImageSide(at, pinhole, "height");
  if (detail::findField(pinhole, "fovyDeg") != nullptr) settings.fovyDeg = readAngle(at, pinhole, "fovyDeg", 45.0);
  settings.eye = readPoint(at, pinhole, "eye", true);
  settings.lookAt = readPoint(at, pinhole, "lookAt", true);
  if (auto up = readPoint(at, pinhole, "up", false)) {
    if (glm::length(*up) == 0.0)
      detail::throwFieldError(at, "up", detail::findField(pinhole, "up"), "expected a non-zero [x, y, z] up vector");
    settings.up = *up;
  }
  if (detail::findField(pinhole, "distortion") != nullptr) {
    settings.distortion = parseLensDistortion(at.child("distortion"), requireObject(at, pinhole, "distortion"));
  }
  return settings;
}

// "panel": {"output": NAME} or {"geometry": "WxH+X+Y"} (panel_placement.h). The geometry must be the calibration's
// screenW x screenH: the panel's pixels map 1:1 to the frame.
PanelPlacement readPanel(const JsonLocation& at, const json& panel, const DisplayConfig& config) {
  detail::rejectUnknownKeys(at, panel, {"output", "geometry"});
  PanelPlacement placement;
  const json* output = detail::findField(panel, "output");
  if (output != nullptr) {
    if (!output->is_string() || output->get<std::string>().empty())
      detail::throwFieldError(at, "output", output,
                              "expected a RandR output or monitor name as `xrandr --listmonitors` prints it, e.g. "
                              "\"HDMI-1\"");
    placement.output = output->get<std::string>();
  }
  const json* geometry = detail::findField(panel, "geometry");
  if (geometry == nullptr) return placement;
  const std::string expected =
      "expected the panel's monitor as WIDTHxHEIGHT+X+Y (xrandr notation, e.g. \"1536x2048+1920+0\")";
  if (!geometry->is_string()) detail::throwFieldError(at, "geometry", geometry, expected);
  placement.geometryText = geometry->get<std::string>();
  placement.geometry = parsePanelGeometry(placement.geometryText);
  if (!placement.geometry) detail::throwFieldError(at, "geometry", geometry, expected);
  if (placement.output)
    detail::throwFieldError(at, "geometry", geometry, "expected an output or a geometry, not both (remove one)");
  const LookingGlassCalibration& c = *config.calibration;
  if (placement.geometry->width != c.screenW || placement.geometry->height != c.screenH) {
    detail::throwFieldError(at, "geometry", geometry,
                            "expected the calibration's screen size " + std::to_string(c.screenW) + "x" +
                                std::to_string(c.screenH) + " (the panel shows the frame 1:1), e.g. \"" +
                                std::to_string(c.screenW) + "x" + std::to_string(c.screenH) + "+0+0\"");
  }
  return placement;
}

DisplayModel readModel(const JsonLocation& at, const json& root) {
  const json* field = detail::findField(root, "model");
  if (field == nullptr) return DisplayModel::Lenticular;
  if (field->is_string()) {
    if (const DisplayModelRow* row = findConfigModel(field->get<std::string>())) return row->model;
  }
  std::vector<std::string> names;
  for (const DisplayModelRow& row : displayModels()) {
    if (row.inConfigs) names.push_back("\"" + std::string(row.name) + "\"");
  }
  std::string expected = "expected ";
  for (std::size_t i = 0; i < names.size(); ++i) {
    expected += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  detail::throwFieldError(at, "model", field, expected);
}

// "a" or "an" before a section name in errors.
std::string withArticle(std::string_view word) {
  const bool vowel = !word.empty() && std::string_view("aeiouAEIOU").find(word.front()) != std::string_view::npos;
  return (vowel ? "an " : "a ") + std::string(word);
}

// "calibration": an embedded visual.json object, or a path to one relative to the config file.
LookingGlassCalibration readCalibration(const JsonLocation& at, const json& field,
                                        const std::filesystem::path& baseDir) {
  if (field.is_object()) return parseLookingGlassCalibration(field, at.file, at.field("calibration"));
  if (!field.is_string())
    detail::throwFieldError(at, "calibration", &field, "expected a visual.json object or a path to a visual.json");
  std::filesystem::path path = field.get<std::string>();
  if (path.is_relative()) path = baseDir / path;
  std::string text = detail::readTextFile(path.string(), at.file, at.field("calibration"),
                                          "expected a readable visual.json, path relative to the config file "
                                          "(resolved to " +
                                              path.string() + ")");
  return parseLookingGlassCalibrationText(text, path.string());
}

// Checks that need several fields: the cone with depthiness must stay below 180 degrees (tan(theta) finite).
void validateCombination(const JsonLocation& at, const json& root, const DisplayConfig& config) {
  if (config.model == DisplayModel::Lenticular && !config.calibration)
    detail::throwFieldError(at, "calibration", nullptr,
                            "expected a visual.json object or a path to a visual.json (required for model "
                            "\"lenticular\")");
  // A model's own section is required for it and rejected for every other model.
  for (const DisplayModelRow& row : displayModels()) {
    if (row.sectionKey.empty()) continue;
    const bool ownModel = config.model == row.model;
    if (ownModel == row.hasSection(config)) continue;
    const std::string section = withArticle(row.sectionKey) + " section";
    const std::string model = "\"" + std::string(row.name) + "\"";
    detail::throwFieldError(at, row.sectionKey, detail::findField(root, row.sectionKey),
                            ownModel
                                ? "expected " + section + " (required for model " + model + ")"
                                : "expected no " + std::string(row.sectionKey) + " section unless model is " + model);
  }
  const bool rayTableModel = config.model == DisplayModel::RayTable;
  // One size source each: an explicit oblique window replaces camera.size; a ray table is sized by rayTable.units.
  const json* cameraSection = detail::findField(root, "camera");
  const json* cameraSize = cameraSection ? detail::findField(*cameraSection, "size") : nullptr;
  if (config.camera.size && config.oblique && config.oblique->windowWidth)
    detail::throwFieldError(at.child("camera"), "size", cameraSize,
                            "expected camera.size \"auto\" or absent when oblique.window is given (one of the two "
                            "sets the window size)");
  if (config.camera.size && rayTableModel)
    detail::throwFieldError(at.child("camera"), "size", cameraSize,
                            "expected camera.size \"auto\" or absent for model \"ray-table\" (the table is scaled "
                            "by rayTable.units)");
  if (config.calibration && config.calibration->viewCone * config.camera.depthiness >= 180.0) {
    const json* camera = detail::findField(root, "camera");
    detail::throwFieldError(at.child("camera"), "depthiness",
                            camera ? detail::findField(*camera, "depthiness") : nullptr,
                            "expected viewCone * depthiness < 180 degrees (viewCone is " +
                                detail::formatNumber(config.calibration->viewCone) + ")");
  }
}

DisplayConfig fromVisualJson(const json& root, const std::string& sourceName) {
  DisplayConfig config;
  config.calibration = parseLookingGlassCalibration(root, sourceName);
  config.name = config.calibration->serial.empty() ? std::filesystem::path(sourceName).stem().string()
                                                   : config.calibration->serial;
  config.description = "raw visual.json " + sourceName;
  config.sourcePath = sourceName;
  return config;
}

// "progressive": the stop rule of progressive streams (docs/SERVICE.md §4.1).
void readProgressive(const JsonLocation& parent, const json& object, DisplayConfig& config) {
  const JsonLocation at = parent.child("progressive");
  detail::rejectUnknownKeys(at, object, {"target_error", "max_spp"});
  config.progressiveTargetError = detail::optionalNumber(at, object, "target_error", false, "a number in [0, 1000]");
  if (config.progressiveTargetError &&
      !(*config.progressiveTargetError >= 0.0 && *config.progressiveTargetError <= 1000.0)) {
    throw ConfigError(at.file, at.field("target_error"), std::to_string(*config.progressiveTargetError),
                      "a number in [0, 1000]");
  }
  if (auto maxSpp = detail::optionalInteger(at, object, "max_spp", false, 1, 1 << 20))
    config.progressiveMaxSpp = static_cast<std::uint32_t>(*maxSpp);
}

DisplayConfig fromOurFormat(const json& root, const std::string& sourceName, const std::filesystem::path& baseDir) {
  const JsonLocation at{sourceName, ""};
  std::vector<std::string_view> keys = {"name", "description", "model",   "calibration", "camera",
                                        "spp",  "progressive", "pinhole", "panel"};
  for (const DisplayModelRow& row : displayModels()) {
    if (!row.sectionKey.empty()) keys.push_back(row.sectionKey);
  }
  detail::rejectUnknownKeys(at, root, keys);
  DisplayConfig config;
  config.sourcePath = sourceName;
  config.name = detail::optionalString(at, root, "name").value_or(std::filesystem::path(sourceName).stem().string());
  config.description = detail::optionalString(at, root, "description").value_or("");
  config.model = readModel(at, root);
  if (const json* calibration = detail::findField(root, "calibration"))
    config.calibration = readCalibration(at, *calibration, baseDir);
  if (detail::findField(root, "camera") != nullptr)
    config.camera = readCamera(at.child("camera"), requireObject(at, root, "camera"));
  if (auto spp = detail::optionalInteger(at, root, "spp", false, 1, kMaxSpp))
    config.spp = static_cast<std::uint32_t>(*spp);
  if (detail::findField(root, "progressive") != nullptr)
    readProgressive(at, requireObject(at, root, "progressive"), config);
  if (detail::findField(root, "pinhole") != nullptr)
    config.pinhole = readPinhole(at.child("pinhole"), requireObject(at, root, "pinhole"));
  for (const DisplayModelRow& row : displayModels()) {
    if (row.sectionKey.empty() || detail::findField(root, row.sectionKey) == nullptr) continue;
    row.parseSection(at.child(row.sectionKey), requireObject(at, root, row.sectionKey), baseDir, config);
  }
  validateCombination(at, root, config);
  if (const json* panel = detail::findField(root, "panel")) {
    if (config.model != DisplayModel::Lenticular)
      detail::throwFieldError(at, "panel", panel, "expected no panel section unless model is \"lenticular\"");
    config.panel = readPanel(at.child("panel"), requireObject(at, root, "panel"), config);
  }
  return config;
}

}  // namespace

DisplayConfig parseDisplayConfig(std::string_view text, const std::string& sourceName,
                                 const std::filesystem::path& baseDir) {
  json root = detail::parseJsonText(text, sourceName);
  if (!root.is_object())
    throw ConfigError(sourceName, "(root)", detail::valueText(&root),
                      "expected a JSON object (a holotrace display config or a visual.json)");
  if (looksLikeVisualJson(root)) return fromVisualJson(root, sourceName);
  return fromOurFormat(root, sourceName, baseDir);
}

DisplayConfig loadDisplayConfig(const std::filesystem::path& file) {
  std::string text = detail::readTextFile(file.string(), file.string(), "(file)",
                                          "expected an existing, readable display config or visual.json");
  return parseDisplayConfig(text, file.string(), file.parent_path());
}

std::vector<std::string> builtinDisplayNames() {
  std::vector<std::string> names;
  for (const detail::EmbeddedDisplayConfig& entry : detail::embeddedDisplayConfigs()) names.emplace_back(entry.name);
  return names;
}

DisplayConfig builtinDisplay(std::string_view name) {
  for (const detail::EmbeddedDisplayConfig& entry : detail::embeddedDisplayConfigs()) {
    if (entry.name == name) return parseDisplayConfig(entry.json, "builtin:" + std::string(name), {});
  }
  std::string known;
  for (const std::string& n : builtinDisplayNames()) known += (known.empty() ? "" : ", ") + n;
  throw ConfigError("builtin:" + std::string(name), "(display)", "\"" + std::string(name) + "\"",
                    "expected one of the built-in displays: " + known);
}

DisplayConfig resolveDisplay(const std::string& spec) {
  constexpr std::string_view kBuiltinPrefix = "builtin:";
  if (spec.rfind(kBuiltinPrefix, 0) == 0) return builtinDisplay(std::string_view(spec).substr(kBuiltinPrefix.size()));
  return loadDisplayConfig(spec);
}

}  // namespace ht
