// looking_glass_calibration.cpp - visual.json parsing and validation (docs/OPTICS.md §1).
#include "camera_models/looking_glass_calibration.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "camera_models/camera_params.h"
#include "camera_models/json_fields.h"
#include "common/error.h"

namespace ht {

using detail::JsonLocation;
using nlohmann::json;

glm::dvec2 SubpixelCell::offset(std::uint32_t channel) const {
  if (channel == 0) return {ROffsetX, ROffsetY};
  if (channel == 1) return {GOffsetX, GOffsetY};
  return {BOffsetX, BOffsetY};
}

namespace {

constexpr long long kMaxScreenSize = 32768;
constexpr double kMaxCellOffsetPx = 2.0;
constexpr int kMaxCellPatternMode = 4;

std::string readVersion(const JsonLocation& at, const json& object) {
  const json* field = detail::findField(object, "configVersion");
  if (field == nullptr) return "";
  const json& value = detail::unwrapValue(*field);
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number()) return detail::formatNumber(value.get<double>());
  detail::throwFieldError(at, "configVersion", field, "expected a version string such as \"1.0\" or \"3.0\"");
}

double requirePositive(const JsonLocation& at, const json& object, std::string_view key, const std::string& what) {
  std::string expected = "expected a finite number > 0 (" + what + ")";
  double value = detail::requireNumber(at, object, key, true, expected);
  if (!(value > 0.0)) detail::throwFieldError(at, key, detail::findField(object, key), expected);
  return value;
}

// Accepts "CellPatternMode" (the real key) and "cellPatternMode" (LKG-Toolkit Calibration.cs Parse).
int readCellPatternMode(const JsonLocation& at, const json& object) {
  for (std::string_view key : {"CellPatternMode", "cellPatternMode"}) {
    std::optional<long long> mode = detail::optionalInteger(at, object, key, true, 0, kMaxCellPatternMode);
    if (mode) return static_cast<int>(*mode);
  }
  return 0;
}

double readCellOffset(const JsonLocation& at, const json& cell, std::string_view key) {
  std::string expected = "expected a finite offset in pixels within [-2, 2]";
  double value = detail::requireNumber(at, cell, key, true, expected);
  if (std::fabs(value) > kMaxCellOffsetPx) detail::throwFieldError(at, key, detail::findField(cell, key), expected);
  return value;
}

SubpixelCell readCell(const JsonLocation& at, const json& cell) {
  if (!cell.is_object()) detail::throwFieldError(at, "", &cell, "expected an object {ROffsetX, ..., BOffsetY}");
  SubpixelCell result;
  result.ROffsetX = readCellOffset(at, cell, "ROffsetX");
  result.ROffsetY = readCellOffset(at, cell, "ROffsetY");
  result.GOffsetX = readCellOffset(at, cell, "GOffsetX");
  result.GOffsetY = readCellOffset(at, cell, "GOffsetY");
  result.BOffsetX = readCellOffset(at, cell, "BOffsetX");
  result.BOffsetY = readCellOffset(at, cell, "BOffsetY");
  return result;
}

std::vector<SubpixelCell> readCells(const JsonLocation& at, const json& object, int mode) {
  const std::string maxCells = std::to_string(gpu_shared::HT_MAX_SUBPIXEL_CELLS);
  const json* field = detail::findField(object, "subpixelCells");
  std::vector<SubpixelCell> cells;
  if (field != nullptr) {
    if (!field->is_array()) detail::throwFieldError(at, "subpixelCells", field, "expected an array of cells");
    if (field->size() > gpu_shared::HT_MAX_SUBPIXEL_CELLS)
      detail::throwFieldError(
          at, "subpixelCells", field,
          "expected at most " + maxCells + " cells (HT_MAX_SUBPIXEL_CELLS), got " + std::to_string(field->size()));
    for (std::size_t i = 0; i < field->size(); ++i)
      cells.push_back(readCell(at.child("subpixelCells[" + std::to_string(i) + "]"), (*field)[i]));
  }
  if (mode != 0 && cells.empty())
    detail::throwFieldError(at, "subpixelCells", field,
                            "expected 1 to " + maxCells + " cells because CellPatternMode is " + std::to_string(mode) +
                                " (or set CellPatternMode 0)");
  return cells;
}

}  // namespace

LookingGlassCalibration parseLookingGlassCalibration(const json& raw, const std::string& file,
                                                     const std::string& fieldPrefix) {
  const JsonLocation at{file, fieldPrefix};
  if (!raw.is_object())
    throw ConfigError(file, fieldPrefix.empty() ? "(root)" : fieldPrefix, detail::valueText(&raw),
                      "expected a visual.json object");
  LookingGlassCalibration c;
  c.rawJson = raw.dump();
  c.configVersion = readVersion(at, raw);
  c.serial = detail::optionalString(at, raw, "serial").value_or("");
  c.pitch = requirePositive(at, raw, "pitch", "raw lenticular pitch");
  c.slope = detail::requireNumber(at, raw, "slope", true, "expected a finite non-zero number (raw lens slope)");
  if (c.slope == 0.0)
    detail::throwFieldError(at, "slope", detail::findField(raw, "slope"),
                            "expected a finite non-zero number (raw lens slope)");
  c.center = detail::requireNumber(at, raw, "center", true, "expected a finite number (lens phase offset)");
  const std::string coneRange = "expected a finite angle in degrees in (0, 180), full cone";
  c.viewCone = detail::requireNumber(at, raw, "viewCone", true, coneRange);
  if (!(c.viewCone > 0.0 && c.viewCone < 180.0))
    detail::throwFieldError(at, "viewCone", detail::findField(raw, "viewCone"), coneRange);
  c.invView = detail::requireFlag(at, raw, "invView");
  c.verticalAngle = detail::optionalNumber(at, raw, "verticalAngle", true, "expected a finite number").value_or(0.0);
  c.DPI = requirePositive(at, raw, "DPI", "panel dots per inch");
  c.screenW = static_cast<std::uint32_t>(detail::requireInteger(at, raw, "screenW", true, 1, kMaxScreenSize));
  c.screenH = static_cast<std::uint32_t>(detail::requireInteger(at, raw, "screenH", true, 1, kMaxScreenSize));
  c.flipImageX = detail::requireFlag(at, raw, "flipImageX");
  c.flipImageY = detail::requireFlag(at, raw, "flipImageY");
  c.flipSubp = detail::requireFlag(at, raw, "flipSubp");
  c.fringe = detail::optionalNumber(at, raw, "fringe", true, "expected a finite number").value_or(0.0);
  c.cellPatternMode = readCellPatternMode(at, raw);
  c.subpixelCells = readCells(at, raw, c.cellPatternMode);
  return c;
}

LookingGlassCalibration parseLookingGlassCalibrationText(std::string_view text, const std::string& file) {
  return parseLookingGlassCalibration(detail::parseJsonText(text, file), file);
}

LookingGlassCalibration loadLookingGlassCalibration(const std::filesystem::path& file) {
  std::string text =
      detail::readTextFile(file.string(), file.string(), "(file)", "expected an existing, readable visual.json file");
  return parseLookingGlassCalibrationText(text, file.string());
}

bool looksLikeVisualJson(const json& object) {
  return object.is_object() && (object.contains("pitch") || object.contains("slope"));
}

}  // namespace ht
