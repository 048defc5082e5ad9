// looking_glass_calibration.h - a Looking Glass factory calibration (`visual.json`), parsed and validated.
//
// Fields and their meaning: docs/OPTICS.md §1 (LKG-Toolkit Toolkit-API/Device/Calibration.cs, SubpixelCell.cs). The raw
// file is accepted unchanged: numbers bare or wrapped as {"value": x}, configVersion "1.0" or "3.0", booleans as
// 0/1 or true/false, `CellPatternMode` or `cellPatternMode`. Unknown keys are kept (as text) in `rawJson`.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

namespace ht {

// Gen3 OLED subpixel cell: per-channel offsets "measured in pixels on the display" (LKG-Toolkit SubpixelCell.cs).
// +x right, +y up (screen uv, v from the bottom; holoplaycore.js adds offY/screenH to v).
struct SubpixelCell {
  double ROffsetX = 0.0, ROffsetY = 0.0;
  double GOffsetX = 0.0, GOffsetY = 0.0;
  double BOffsetX = 0.0, BOffsetY = 0.0;
  glm::dvec2 offset(std::uint32_t channel) const;  // channel 0, 1, 2 = R, G, B
};

struct LookingGlassCalibration {
  std::string configVersion;   // "1.0" (Gen1, early Portrait) or "3.0" (Gen2/Gen3 templates)
  std::string serial;          // prefix names the device type (LKG-P Portrait, LKG-J 16" Gen3 landscape, ...)
  double pitch = 0.0;          // raw lenticular pitch, lenses per inch across the slanted lens (> 0)
  double slope = 0.0;          // raw lens slant (!= 0), pixels of y per pixel of x along a lens, signed
  double center = 0.0;         // phase offset of the lens pattern, in lenses
  double viewCone = 0.0;       // degrees, full cone (looking-glass-webxr convention), (0, 180)
  bool invView = false;        // reversed view order: t = 1 - fract(phi)
  double verticalAngle = 0.0;  // present in every file seen, read by no known shader; kept
  double DPI = 0.0;            // panel dots per inch (> 0)
  std::uint32_t screenW = 0;   // native panel width in pixels, [1, 32768]
  std::uint32_t screenH = 0;   // native panel height in pixels, [1, 32768]
  bool flipImageX = false;     // mirror horizontally (negates tilt and subp, docs/OPTICS.md §2)
  bool flipImageY = false;     // mirror vertically
  bool flipSubp = false;       // BGR panel: output R/B use the phase of subpixel 2 - c
  double fringe = 0.0;         // Large/Pro fringe correction; optional, default 0; not used by the ray model
  int cellPatternMode = 0;     // CellPatternMode 0 (classic) .. 4 (Gen3 cell layouts, docs/OPTICS.md §3.2)
  std::vector<SubpixelCell> subpixelCells;  // <= 4 cells; >= 1 when cellPatternMode != 0
  std::string rawJson;                      // the file's JSON object as read (compact text), unknown keys included
};

// Parses and validates a visual.json object. `file` names the source in errors; `fieldPrefix` is prepended to field
// names (e.g. "calibration" when embedded in a display config). Throws ConfigError.
LookingGlassCalibration parseLookingGlassCalibration(const nlohmann::json& raw, const std::string& file,
                                                     const std::string& fieldPrefix = "");
LookingGlassCalibration parseLookingGlassCalibrationText(std::string_view text, const std::string& file);
LookingGlassCalibration loadLookingGlassCalibration(const std::filesystem::path& file);

// True when a JSON object looks like a raw visual.json (has a top-level "pitch" or "slope").
bool looksLikeVisualJson(const nlohmann::json& object);

}  // namespace ht
