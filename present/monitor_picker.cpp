// monitor_picker.cpp - the rules of monitor_picker.h, each a small filter over the snapshot's monitors.
#include "present/monitor_picker.h"

#include "camera_models/panel_placement.h"

#include <vector>

namespace ht::present {
namespace {

constexpr const char* kPanelEdidPrefix = "LKG";

// The first output of `monitor` the snapshot knows (its EDID and mode describe the monitor), or nullptr.
const RandrOutput* mainOutput(const RandrSnapshot& snapshot, const RandrMonitor& monitor) {
  for (const std::string& name : monitor.outputs) {
    if (const RandrOutput* o = snapshot.output(name)) return o;
  }
  return nullptr;
}

bool hasPanelEdid(const RandrSnapshot& snapshot, const RandrMonitor& monitor) {
  for (const std::string& name : monitor.outputs) {
    const RandrOutput* o = snapshot.output(name);
    if (o && o->edidMonitorName.rfind(kPanelEdidPrefix, 0) == 0) return true;
  }
  return false;
}

bool hasPanelSize(const RandrMonitor& monitor, const PanelRequest& request) {
  return monitor.rect.width == request.screenWidth && monitor.rect.height == request.screenHeight;
}

std::string panelSize(const PanelRequest& request) {
  return std::to_string(request.screenWidth) + "x" + std::to_string(request.screenHeight);
}

std::string names(const std::vector<const RandrMonitor*>& monitors) {
  std::string text;
  for (const RandrMonitor* m : monitors) text += (text.empty() ? "" : ", ") + m->name + " " + describeRect(m->rect);
  return text;
}

[[noreturn]] void refuse(const RandrSnapshot& snapshot, const std::string& problem) {
  throw PresentError(problem + "; monitors found:\n" + describeMonitors(snapshot));
}

// The chosen monitor must show the frame 1:1.
PickedMonitor accept(const RandrSnapshot& snapshot, const RandrMonitor& monitor, const PanelRequest& request,
                     const char* rule) {
  if (!hasPanelSize(monitor, request)) {
    refuse(snapshot, "monitor " + monitor.name + " (" + rule + ") is " + describeRect(monitor.rect) +
                         ", the calibration's screen is " + panelSize(request) +
                         " (set the panel's mode to its native size, or fix screenW/screenH)");
  }
  for (const std::string& name : monitor.outputs) {
    const RandrOutput* o = snapshot.output(name);
    if (o && o->rotation != 1) {
      refuse(snapshot, "monitor " + monitor.name + " (" + rule + "): output " + name + " is rotated (RandR rotation " +
                           std::to_string(o->rotation) + "); the panel must be shown unrotated (xrandr --output " +
                           name + " --rotate normal)");
    }
    if (o && !o->identityTransform) {
      refuse(snapshot, "monitor " + monitor.name + " (" + rule + "): output " + name +
                           " has a scaling transform; the panel needs 1:1 pixels (xrandr --output " + name +
                           " --transform none --scale 1x1)");
    }
  }
  const RandrOutput* out = mainOutput(snapshot, monitor);
  return PickedMonitor{monitor.name, out ? out->name : "",       out ? out->edidMonitorName : "",
                       monitor.rect, out ? out->refreshHz : 0.0, rule};
}

std::vector<const RandrMonitor*> matching(const RandrSnapshot& snapshot, auto&& predicate) {
  std::vector<const RandrMonitor*> found;
  for (const RandrMonitor& m : snapshot.monitors) {
    if (predicate(m)) found.push_back(&m);
  }
  return found;
}

PickedMonitor pickByName(const RandrSnapshot& snapshot, const PanelRequest& request) {
  const std::string& wanted = *request.output;
  auto found = matching(snapshot, [&](const RandrMonitor& m) { return m.name == wanted; });
  if (found.empty()) {
    found = matching(snapshot, [&](const RandrMonitor& m) {
      for (const std::string& o : m.outputs) {
        if (o == wanted) return true;
      }
      return false;
    });
  }
  if (found.empty()) refuse(snapshot, "no monitor or output named '" + wanted + "'");
  if (found.size() > 1) refuse(snapshot, "output '" + wanted + "' shows several monitors: " + names(found));
  return accept(snapshot, *found[0], request, "output name");
}

PickedMonitor pickByGeometry(const RandrSnapshot& snapshot, const PanelRequest& request) {
  auto found = matching(snapshot, [&](const RandrMonitor& m) { return m.rect == *request.geometry; });
  if (found.empty()) refuse(snapshot, "no monitor at " + describeRect(*request.geometry));
  if (found.size() > 1)
    refuse(snapshot, "several monitors at " + describeRect(*request.geometry) + ": " + names(found));
  return accept(snapshot, *found[0], request, "geometry");
}

}  // namespace

PickedMonitor pickMonitor(const RandrSnapshot& snapshot, const PanelRequest& request) {
  if (request.output) return pickByName(snapshot, request);
  if (request.geometry) return pickByGeometry(snapshot, request);
  auto panels = matching(snapshot, [&](const RandrMonitor& m) { return hasPanelEdid(snapshot, m); });
  auto sized = matching(snapshot, [&](const RandrMonitor& m) { return hasPanelSize(m, request); });
  auto panelsSized =
      matching(snapshot, [&](const RandrMonitor& m) { return hasPanelEdid(snapshot, m) && hasPanelSize(m, request); });
  if (panelsSized.size() > 1) {
    refuse(snapshot, "several LKG monitors of " + panelSize(request) + ": " + names(panelsSized) +
                         "; name one with an output name or geometry in the config");
  }
  if (panelsSized.size() == 1) return accept(snapshot, *panelsSized[0], request, "EDID LKG");
  if (sized.size() > 1) {
    refuse(snapshot, "several monitors of " + panelSize(request) + " and none with an LKG EDID: " + names(sized) +
                         "; name one with an output name or geometry in the config");
  }
  if (sized.size() == 1) return accept(snapshot, *sized[0], request, "size");
  if (!panels.empty()) {
    refuse(snapshot, "LKG monitor " + names(panels) + " is not the calibration's " + panelSize(request) +
                         " (set the panel's native mode, or use the calibration of this panel)");
  }
  refuse(snapshot, "no monitor of " + panelSize(request) + " and none with an LKG EDID name");
}

PanelRequest withPlacement(PanelRequest request, const PanelPlacement& placement) {
  if (request.output || request.geometry) return request;
  request.output = placement.output;
  if (placement.geometry) {
    const PanelGeometry& g = *placement.geometry;
    request.geometry = Rect{g.x, g.y, g.width, g.height};
  }
  return request;
}

Rect parseGeometry(const std::string& text) {
  const std::optional<PanelGeometry> g = parsePanelGeometry(text);
  if (!g) {
    throw PresentError("geometry '" + text +
                       "': expected WIDTHxHEIGHT+X+Y as xrandr prints it, width and height > 0, e.g. 1536x2048+1920+0");
  }
  return Rect{g->x, g->y, g->width, g->height};
}

std::string describeMonitors(const RandrSnapshot& snapshot) {
  if (snapshot.monitors.empty()) return "  (none)";
  std::string text;
  for (const RandrMonitor& m : snapshot.monitors) {
    text += "  " + m.name + " " + describeRect(m.rect);
    for (const std::string& name : m.outputs) {
      const RandrOutput* o = snapshot.output(name);
      text += " (output " + name;
      if (o && !o->edidMonitorName.empty()) text += ", EDID '" + o->edidMonitorName + "'";
      if (o && !o->edidProblem.empty()) text += ", " + o->edidProblem;
      if (o && o->rotation != 1) text += ", rotated";
      if (o && !o->identityTransform) text += ", transformed";
      text += ")";
    }
    text += "\n";
  }
  text.pop_back();
  return text;
}

}  // namespace ht::present
