// present_config.cpp - see present_config.h.
#include "server/present_config.h"

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "present/monitor_picker.h"

namespace ht::server {
namespace {

using nlohmann::json;

std::optional<std::string> optionalString(const json& entry, const char* key, const std::string& field,
                                          const std::string& source) {
  if (!entry.contains(key)) return std::nullopt;
  if (!entry[key].is_string()) throw ConfigError(source, field + "." + key, entry[key].dump(), "a string");
  return entry[key].get<std::string>();
}

PanelTarget parseTarget(const json& entry, std::size_t index, const std::string& source) {
  const std::string field = "present[" + std::to_string(index) + "]";
  if (entry.is_string()) return PanelTarget{entry.get<std::string>(), std::nullopt, std::nullopt};
  if (!entry.is_object() || !entry.contains("display") || !entry["display"].is_string()) {
    throw ConfigError(source, field, entry.dump(),
                      "a display id, or {\"display\": ID, \"output\" or \"geometry\": ...}");
  }
  for (const auto& [key, value] : entry.items()) {
    if (key != "display" && key != "output" && key != "geometry") {
      throw ConfigError(source, field + "." + key, value.dump(), "one of display, output, geometry");
    }
  }
  PanelTarget t{entry["display"].get<std::string>(), optionalString(entry, "output", field, source),
                optionalString(entry, "geometry", field, source)};
  if (t.output && t.geometry) throw ConfigError(source, field, entry.dump(), "an output or a geometry, not both");
  if (t.geometry) {
    try {
      present::parseGeometry(*t.geometry);
    } catch (const present::PresentError& e) { throw ConfigError(source, field + ".geometry", *t.geometry, e.what()); }
  }
  return t;
}

}  // namespace

PresentConfig parsePresentConfig(const json& doc, const std::string& source) {
  PresentConfig c;
  if (doc.contains("x_display")) {
    if (!doc["x_display"].is_string())
      throw ConfigError(source, "x_display", doc["x_display"].dump(), "a string such as \":0\"");
    c.xDisplay = doc["x_display"].get<std::string>();
  }
  if (!doc.contains("present")) return c;
  const json& p = doc["present"];
  if (p.is_string() && (p == "none" || p == "auto")) {
    c.mode = p == "auto" ? PresentConfig::Mode::Auto : PresentConfig::Mode::None;
    return c;
  }
  if (!p.is_array()) throw ConfigError(source, "present", p.dump(), "\"auto\", \"none\" or a list of display ids");
  c.mode = PresentConfig::Mode::List;
  for (std::size_t i = 0; i < p.size(); ++i) {
    PanelTarget t = parseTarget(p[i], i, source);
    for (const PanelTarget& other : c.panels) {
      if (other.displayId == t.displayId) {
        throw ConfigError(source, "present[" + std::to_string(i) + "]", p[i].dump(), "each display at most once");
      }
    }
    c.panels.push_back(std::move(t));
  }
  return c;
}

}  // namespace ht::server
