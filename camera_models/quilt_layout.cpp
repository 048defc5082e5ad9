// quilt_layout.cpp - quilt names, tile layout and device defaults (see quilt_layout.h; docs/OPTICS.md §4.1, §4.2).
#include "camera_models/quilt_layout.h"

#include <charconv>
#include <cmath>
#include <regex>

#include "camera_models/json_fields.h"
#include "common/error.h"

namespace ht {

namespace {

constexpr std::uint32_t kMaxQuiltCount = 1024;
constexpr const char* kQuiltNameField = "quilt name";
constexpr const char* kQuiltNameExpected =
    "expected a quilt tag _qs{columns}x{rows}a{aspect} or _qs{columns}x{rows} (columns, rows in [1, 1024], aspect > 0)";

[[noreturn]] void throwBadName(std::string_view fileName) {
  throw ConfigError(std::string(fileName), kQuiltNameField, "\"" + std::string(fileName) + "\"", kQuiltNameExpected);
}

std::uint32_t parseCount(const std::string& digits, std::string_view fileName) {
  if (digits.size() > 5) throwBadName(fileName);
  const unsigned long value = std::stoul(digits);
  if (value == 0 || value > kMaxQuiltCount) throwBadName(fileName);
  return static_cast<std::uint32_t>(value);
}

}  // namespace

QuiltName parseQuiltName(std::string_view fileName) {
  // looking-glass-webxr LookingGlassMediaController.ts: `_qs(\d+)x(\d+)a([\d.]+)`; bridge.js also takes `_qs8x13`.
  // The aspect group here is any run of digits and dots so that "a1.2.3" is reported, not half-read; one trailing
  // dot belongs to the file extension.
  static const std::regex tag(R"(_qs(\d+)x(\d+)(a([0-9.]*))?)");
  const std::string text(fileName);
  std::smatch last;
  bool found = false;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), tag); it != std::sregex_iterator(); ++it) {
    last = *it;
    found = true;
  }
  if (!found) throwBadName(fileName);
  QuiltName name;
  name.columns = parseCount(last[1].str(), fileName);
  name.rows = parseCount(last[2].str(), fileName);
  if (last[3].matched) {
    std::string aspect = last[4].str();
    if (!aspect.empty() && aspect.back() == '.') aspect.pop_back();  // "a0.75.png": the dot before the extension
    double value = 0.0;
    const auto [end, error] = std::from_chars(aspect.data(), aspect.data() + aspect.size(), value);
    if (aspect.empty() || error != std::errc() || end != aspect.data() + aspect.size() || !std::isfinite(value) ||
        !(value > 0.0))
      throwBadName(fileName);
    name.aspect = value;
  }
  return name;
}

bool hasQuiltTag(std::string_view fileName) {
  static const std::regex tag(R"(_qs\d+x\d+)");
  return std::regex_search(std::string(fileName), tag);
}

std::string formatQuiltName(std::uint32_t columns, std::uint32_t rows, double aspect) {
  // Fixed notation only: the parser reads digits and dots. The longest shortest-round-trip fixed form of a double is
  // 309 integer digits (DBL_MAX) or "0." + 323 zeros + "5" (the smallest denormal), so 400 chars always suffice;
  // a 64-char buffer sent aspects >= 1e63 to the exponent form, which parseQuiltName refuses (found by fuzzing).
  char buffer[400];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), aspect, std::chars_format::fixed);
  const std::string aspectText = error == std::errc() ? std::string(buffer, end) : detail::formatNumber(aspect);
  return "_qs" + std::to_string(columns) + "x" + std::to_string(rows) + "a" + aspectText;
}

QuiltLayout makeQuiltLayout(std::uint32_t columns, std::uint32_t rows, std::uint32_t quiltWidth,
                            std::uint32_t quiltHeight, double aspect) {
  const std::string source = "quilt";
  if (columns == 0 || columns > kMaxQuiltCount)
    throw ConfigError(source, "columns", std::to_string(columns), "expected an integer in [1, 1024]");
  if (rows == 0 || rows > kMaxQuiltCount)
    throw ConfigError(source, "rows", std::to_string(rows), "expected an integer in [1, 1024]");
  if (quiltWidth < columns)
    throw ConfigError(source, "quiltWidth", std::to_string(quiltWidth), "expected at least one pixel per column");
  if (quiltHeight < rows)
    throw ConfigError(source, "quiltHeight", std::to_string(quiltHeight), "expected at least one pixel per row");
  if (!std::isfinite(aspect) || !(aspect > 0.0))
    throw ConfigError(source, "aspect", detail::formatNumber(aspect), "expected a finite render aspect W/H > 0");
  return {columns, rows, quiltWidth, quiltHeight, quiltWidth / columns, quiltHeight / rows, aspect};
}

QuiltLayout defaultQuiltLayout(const DisplayConfig& config) {
  if (config.model != DisplayModel::Lenticular || !config.calibration)
    throw ConfigError(config.sourcePath, "model", std::string(displayModelName(config.model)),
                      "expected a lenticular display (device default quilts exist only for Looking Glass panels)");
  const LookingGlassCalibration& c = *config.calibration;
  const double aspect = double(c.screenW) / double(c.screenH);
  if (const auto& q = config.camera.quilt) return makeQuiltLayout(q->columns, q->rows, q->width, q->height, aspect);
  const bool gen3 = c.cellPatternMode != 0;
  const auto is = [&](std::uint32_t w, std::uint32_t h) { return c.screenW == w && c.screenH == h; };
  // docs/OPTICS.md §4.2 (LKG-Toolkit HardCodedLKGDeviceTemplates.cs; looking-glass-webxr quiltResolution).
  if (is(1536, 2048)) return makeQuiltLayout(8, 6, 3360, 3360, aspect);           // Portrait
  if (is(1440, 2560)) return makeQuiltLayout(11, 6, 4092, 4092, aspect);          // Go
  if (gen3 && is(3840, 2160)) return makeQuiltLayout(7, 7, 6000, 6000, aspect);   // 16" Gen3 landscape
  if (gen3 && is(2160, 3840)) return makeQuiltLayout(11, 6, 6000, 6000, aspect);  // 16" Gen3 portrait
  if (gen3 && is(7680, 4320)) return makeQuiltLayout(7, 7, 8190, 8190, aspect);   // 32" Gen3 landscape
  if (gen3 && is(4320, 7680)) return makeQuiltLayout(11, 6, 8184, 8184, aspect);  // 32" Gen3 portrait
  if (is(7680, 4320)) return makeQuiltLayout(5, 9, 8192, 8192, aspect);           // 32" Gen2
  return makeQuiltLayout(5, 9, 4096, 4096, aspect);                               // 8.9" / 15.6" / 16" Gen2
}

glm::uvec2 quiltTileOrigin(const QuiltLayout& layout, std::uint32_t view) {
  return {(view % layout.columns) * layout.tileWidth, (view / layout.columns) * layout.tileHeight};
}

glm::dvec2 quiltUV(const QuiltLayout& layout, std::uint32_t view, glm::dvec2 tileUV) {
  const double portionX = double(layout.columns) * layout.tileWidth / layout.quiltWidth;
  const double portionY = double(layout.rows) * layout.tileHeight / layout.quiltHeight;
  const double tileX = view % layout.columns, tileY = view / layout.columns;
  return {(tileX + tileUV.x) / layout.columns * portionX, (tileY + tileUV.y) / layout.rows * portionY};
}

std::optional<QuiltTilePixel> quiltTilePixel(const QuiltLayout& layout, glm::uvec2 quiltPixel) {
  const std::uint32_t tileX = quiltPixel.x / layout.tileWidth, tileY = quiltPixel.y / layout.tileHeight;
  if (tileX >= layout.columns || tileY >= layout.rows) return std::nullopt;
  return QuiltTilePixel{tileY * layout.columns + tileX,
                        {quiltPixel.x % layout.tileWidth, quiltPixel.y % layout.tileHeight}};
}

}  // namespace ht
