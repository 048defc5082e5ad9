// panel_placement.h - the optional "panel" section of a holotrace display config: which monitor of the X screen shows
// this panel, when the automatic choice (EDID name starting with LKG, or the only monitor of the panel's size) is not
// enough, e.g. several panels on one host (docs/configs.md "Panel placement", docs/DISPLAY.md "Presenting to the
// panel" §2). Plain data: the display sink (present/) turns it into its monitor request; a daemon config's "present"
// entry overrides it.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ht {

// A rectangle on the X screen as xrandr prints it: "WIDTHxHEIGHT+X+Y" (X, Y may be negative: "-1920").
struct PanelGeometry {
  std::int32_t x = 0, y = 0;
  std::uint32_t width = 0, height = 0;
  bool operator==(const PanelGeometry&) const = default;
};

// nullopt unless `text` is WIDTHxHEIGHT+X+Y with width, height in [1, 99999] and |X|, |Y| <= 99999.
std::optional<PanelGeometry> parsePanelGeometry(std::string_view text);

struct PanelPlacement {
  std::optional<std::string> output;      // RandR output or monitor name ("HDMI-1", "DP-2", "LKG-P")
  std::optional<PanelGeometry> geometry;  // the monitor's rectangle
  std::string geometryText;               // as written (messages)
};

}  // namespace ht
