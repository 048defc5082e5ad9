// randr_snapshot.h - what X RandR says about the screens of one X server, as plain data: the RandR 1.5 monitors
// (the rectangles a desktop shows windows on) and the outputs (connectors) with their EDID, mode and rotation. The
// monitor picker (monitor_picker.h) works on this data only, so it is tested on hand-made snapshots; randr_reader.h
// fills it from a live server.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ht::present {

struct Rect {
  std::int32_t x = 0, y = 0;
  std::uint32_t width = 0, height = 0;
  bool operator==(const Rect&) const = default;
};

// "1536x2048+1920+0", the notation of xrandr.
std::string describeRect(const Rect& rect);

struct RandrOutput {
  std::string name;  // "HDMI-1", "screen" (Xvfb)
  bool connected = false;
  std::string edidMonitorName;  // EDID display descriptor 0xFC ("LKG-P00671"), "" if none
  std::string edidProblem;      // why the EDID could not be read ("" when fine or absent)
  Rect crtc;                    // the CRTC's rectangle; empty when the output is off
  std::uint32_t modeWidth = 0, modeHeight = 0;
  double refreshHz = 0.0;         // dotClock / (hTotal x vTotal) of the CRTC's mode; 0 unknown
  std::uint16_t rotation = 1;     // RandR rotation bits; 1 = normal (Rotate_0), anything else is refused
  bool identityTransform = true;  // false when the CRTC has a scaling / projective transform
};

struct RandrMonitor {
  std::string name;  // RandR 1.5 monitor name ("LKG-P", "HDMI-1", "MAIN")
  Rect rect;         // on the X screen, in pixels
  bool primary = false;
  bool automatic = false;            // made by the server for an output (not by `xrandr --setmonitor`)
  std::vector<std::string> outputs;  // names of the outputs the monitor shows
};

struct RandrSnapshot {
  std::vector<RandrMonitor> monitors;
  std::vector<RandrOutput> outputs;

  const RandrOutput* output(const std::string& name) const;
};

}  // namespace ht::present
