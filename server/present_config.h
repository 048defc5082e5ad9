// present_config.h - the daemon config's "present" section: which displays get a panel sink (docs/SERVICE.md §11).
//   "present": "none"                         no panel sinks (the default)
//   "present": "auto"                         every lenticular display of displays_dir (the user's own panels)
//   "present": ["portrait", {"display": "gen1", "output": "HDMI-1"}, {"display": "go", "geometry": "1440x2560+0+0"}]
//   "x_display": ":0"                         the X server to present on (default $DISPLAY)
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace ht::server {

struct PanelTarget {
  std::string displayId;
  std::optional<std::string> output;    // RandR output or monitor name
  std::optional<std::string> geometry;  // "WxH+X+Y"
};

struct PresentConfig {
  enum class Mode { None, Auto, List };
  Mode mode = Mode::None;
  std::vector<PanelTarget> panels;  // Mode::List
  std::string xDisplay;             // "" = $DISPLAY
};

// Reads "present" and "x_display" of the config document. Throws ConfigError naming the field.
PresentConfig parsePresentConfig(const nlohmann::json& doc, const std::string& source);

}  // namespace ht::server
