// monitor_picker.h - which RandR monitor is the panel: a pure function of a RandR snapshot and what the display
// config / daemon config asks for. Rules, first that applies (docs/DISPLAY.md "Presenting to the panel"):
//   1. an explicit output or monitor name in the request: that monitor;
//   2. an explicit geometry (WxH+X+Y): the monitor with exactly that rectangle;
//   3. the monitors showing an output whose EDID monitor name starts with "LKG" and whose size is the calibration's
//      screenW x screenH: exactly one must exist;
//   4. else the single monitor of exactly screenW x screenH.
// The chosen monitor must be screenW x screenH, shown unrotated and untransformed: the panel's pixels map 1:1 to the
// frame. Anything else (none, several, rotated, wrong size) throws PresentError naming every monitor found.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "camera_models/panel_placement.h"
#include "present/present_error.h"
#include "present/randr_snapshot.h"

namespace ht::present {

struct PanelRequest {
  std::uint32_t screenWidth = 0, screenHeight = 0;  // the calibration's screenW x screenH
  std::optional<std::string> output;                // explicit output or monitor name ("HDMI-1", "LKG-P")
  std::optional<Rect> geometry;                     // explicit rectangle on the X screen
};

struct PickedMonitor {
  std::string monitor;     // RandR monitor name
  std::string output;      // the output showing it ("" for a monitor without outputs)
  std::string edidName;    // that output's EDID monitor name, "" if none
  Rect rect;               // where the window goes, 1:1
  double refreshHz = 0.0;  // of the output's mode; 0 unknown
  std::string rule;        // which rule chose it: "output name", "geometry", "EDID LKG", "size"
  bool operator==(const PickedMonitor&) const = default;
};

// Throws PresentError (see above).
PickedMonitor pickMonitor(const RandrSnapshot& snapshot, const PanelRequest& request);

// `request` with the output / geometry of a display config's "panel" section (camera_models/panel_placement.h); a
// request that already names an output or geometry (command line, daemon config) is returned unchanged.
PanelRequest withPlacement(PanelRequest request, const PanelPlacement& placement);

// "WxH+X+Y" -> Rect; throws PresentError naming `text`.
Rect parseGeometry(const std::string& text);

// One line per monitor for messages: "LKG-P 1536x2048+1920+0 (output screen, EDID 'LKG-P0001')".
std::string describeMonitors(const RandrSnapshot& snapshot);

}  // namespace ht::present
