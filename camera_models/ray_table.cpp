// ray_table.cpp - the "rayTable" section, RayTable validation, RayTableParams and the double reference.
#include "camera_models/ray_table.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "camera_models/display_config.h"
#include "common/error.h"

namespace ht {

using detail::JsonLocation;
using nlohmann::json;

namespace {

constexpr double kUnitTolerance = 4e-7;  // a few float ulps of 1: float-normalised vectors stay as they are

std::string entryName(const char* what, std::uint32_t x, std::uint32_t y) {
  return std::string(what) + "[x=" + std::to_string(x) + ", y=" + std::to_string(y) + "]";
}

std::string vecText(const glm::vec3& v) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

const RayTableConfig& requireRayTable(const DisplayConfig& config) {
  if (config.model != DisplayModel::RayTable || !config.rayTable)
    throw ConfigError(config.sourcePath, "model", "\"" + std::string(displayModelName(config.model)) + "\"",
                      "expected model \"ray-table\" with a rayTable section");
  return *config.rayTable;
}

}  // namespace

RayTableConfig parseRayTable(const JsonLocation& at, const json& section, const std::filesystem::path& baseDir) {
  detail::rejectUnknownKeys(at, section, {"file", "units"});
  RayTableConfig c;
  const json* file = detail::findField(section, "file");
  if (file == nullptr || !file->is_string() || file->get<std::string>().empty())
    detail::throwFieldError(at, "file", file,
                            "expected the path of a ray-table EXR (channels origin.X/Y/Z, direction.X/Y/Z), relative "
                            "to the config file");
  c.file = file->get<std::string>();
  if (c.file.is_relative() && !baseDir.empty()) c.file = baseDir / c.file;
  const std::string expected = "expected world units per table unit, a finite number > 0";
  if (detail::findField(section, "units") != nullptr)
    c.units = detail::requirePositiveNumber(at, section, "units", expected);
  return c;
}

void checkRayTableSize(std::uint64_t width, std::uint64_t height, const std::string& source) {
  if (width < 1 || height < 1 || width > kMaxRayTableSize || height > kMaxRayTableSize)
    throw ConfigError(source, "size", std::to_string(width) + "x" + std::to_string(height),
                      "expected a ray table of 1x1 to " + std::to_string(kMaxRayTableSize) + "x" +
                          std::to_string(kMaxRayTableSize) + " entries (one per pixel)");
}

void RayTable::validate(const std::string& source) const {
  checkRayTableSize(width, height, source);
  const std::size_t count = std::size_t(width) * height;
  if (origins.size() != count || directions.size() != count)
    throw ConfigError(source, "entries",
                      std::to_string(origins.size()) + " origins, " + std::to_string(directions.size()) + " directions",
                      "expected width*height = " + std::to_string(count) + " of each");
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const std::size_t i = index(x, y);
      if (!finite(origins[i]))
        throw ConfigError(source, entryName("origin", x, y), vecText(origins[i]), "expected finite numbers");
      if (!finite(directions[i]) || glm::length(glm::dvec3(directions[i])) == 0.0)
        throw ConfigError(source, entryName("direction", x, y), vecText(directions[i]),
                          "expected a finite, non-zero direction");
    }
  }
  // Each 2x2 cell is interpolated: pairwise angles below 90 degrees keep every convex combination away from zero
  // (|sum w_i d_i|^2 = sum w_i w_j d_i.d_j > 0 when all d_i.d_j > 0).
  // (Only the sign of the dot product matters, so the directions need not be unit length here.)
  auto at = [&](std::uint32_t x, std::uint32_t y) { return glm::dvec3(directions[index(x, y)]); };
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const std::uint32_t x1 = std::min(x + 1, width - 1), y1 = std::min(y + 1, height - 1);
      const std::uint32_t pairs[4][4] = {{x, y, x1, y}, {x, y, x, y1}, {x, y, x1, y1}, {x1, y, x, y1}};
      for (const auto& q : pairs) {
        if (glm::dot(at(q[0], q[1]), at(q[2], q[3])) <= 0.0)
          throw ConfigError(source, entryName("direction", q[2], q[3]), vecText(directions[index(q[2], q[3])]),
                            "expected neighbouring directions less than 90 degrees apart (neighbour " +
                                entryName("direction", q[0], q[1]) + " = " + vecText(directions[index(q[0], q[1])]) +
                                ")");
      }
    }
  }
}

void RayTable::normalizeDirections() {
  for (glm::vec3& d : directions) {
    const glm::dvec3 v(d);
    const double length = glm::length(v);
    if (std::fabs(length - 1.0) > kUnitTolerance) d = glm::vec3(v / length);
  }
}

glm::dvec3 resolveRayTableTarget(const DisplayConfig& config, const Bounds3& sceneBounds) {
  requireRayTable(config);
  return config.camera.target.value_or(
      sceneBounds.empty() ? glm::dvec3(0.0) : 0.5 * (glm::dvec3(sceneBounds.lo) + glm::dvec3(sceneBounds.hi)));
}

gpu_shared::RayTableParams makeRayTableParams(const DisplayConfig& config, const RayTable& table,
                                              const Bounds3& sceneBounds) {
  const RayTableConfig& c = requireRayTable(config);
  checkRayTableSize(table.width, table.height, c.file.string());
  gpu_shared::RayTableParams p{};
  p.size = glm::ivec4(static_cast<int>(table.width), static_cast<int>(table.height), 0, 0);
  p.localToWorld = glm::mat4(1.0f);
  p.localToWorld[3] = glm::vec4(glm::dvec4(resolveRayTableTarget(config, sceneBounds), 1.0));
  p.scale = glm::vec4(static_cast<float>(c.units), 0.0f, 0.0f, 0.0f);
  return p;
}

RayTableReference::RayTableReference(const DisplayConfig& config, const RayTable& table, const Bounds3& sceneBounds)
    : table_(&table), units_(requireRayTable(config).units), target_(resolveRayTableTarget(config, sceneBounds)) {}

ReferenceRay RayTableReference::ray(std::uint32_t x, std::uint32_t y, glm::dvec2 xi) const {
  const RayTable& t = *table_;
  // Sample position in entry coordinates (entry k at k), clamped to the table; weights from the fractional part.
  const double qx = std::clamp(x + xi.x - 0.5, 0.0, t.width - 1.0);
  const double qy = std::clamp(y + xi.y - 0.5, 0.0, t.height - 1.0);
  const auto x0 = static_cast<std::uint32_t>(std::min(std::floor(qx), std::max(t.width - 2.0, 0.0)));
  const auto y0 = static_cast<std::uint32_t>(std::min(std::floor(qy), std::max(t.height - 2.0, 0.0)));
  const std::uint32_t x1 = std::min(x0 + 1, t.width - 1), y1 = std::min(y0 + 1, t.height - 1);
  const double fx = x1 == x0 ? 0.0 : qx - x0, fy = y1 == y0 ? 0.0 : qy - y0;
  auto blend = [&](const std::vector<glm::vec3>& v) {
    const glm::dvec3 a00(v[t.index(x0, y0)]), a10(v[t.index(x1, y0)]), a01(v[t.index(x0, y1)]), a11(v[t.index(x1, y1)]);
    return (1.0 - fy) * ((1.0 - fx) * a00 + fx * a10) + fy * ((1.0 - fx) * a01 + fx * a11);
  };
  return {target_ + units_ * blend(t.origins), glm::normalize(blend(t.directions))};
}

}  // namespace ht
