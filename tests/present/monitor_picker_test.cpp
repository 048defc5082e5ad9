// monitor_picker_test.cpp - the monitor rules on hand-made RandR snapshots: EDID match, size match, explicit name and
// geometry, ties, rotation, transforms, size mismatches and the messages that name what was found.
#include <gtest/gtest.h>

#include "present/monitor_picker.h"

namespace ht::present {
namespace {

RandrOutput output(std::string name, std::string edid, double hz = 60.0) {
  RandrOutput o;
  o.name = std::move(name);
  o.connected = true;
  o.edidMonitorName = std::move(edid);
  o.refreshHz = hz;
  return o;
}

RandrMonitor monitor(std::string name, Rect rect, std::vector<std::string> outputs) {
  return RandrMonitor{std::move(name), rect, false, false, std::move(outputs)};
}

// A desktop monitor and a Portrait panel side by side, as on a developer's desk.
RandrSnapshot desk() {
  RandrSnapshot s;
  s.outputs = {output("DP-1", "DELL U2720Q"), output("HDMI-1", "LKG-P00671", 59.94)};
  s.monitors = {monitor("DP-1", {0, 0, 1920, 1080}, {"DP-1"}), monitor("HDMI-1", {1920, 0, 1536, 2048}, {"HDMI-1"})};
  return s;
}

PanelRequest portrait() { return PanelRequest{1536, 2048, std::nullopt, std::nullopt}; }

std::string errorOf(const RandrSnapshot& s, const PanelRequest& r) {
  try {
    pickMonitor(s, r);
  } catch (const PresentError& e) { return e.what(); }
  return "";
}

TEST(MonitorPicker, EdidNameAndSizeFindThePanel) {
  PickedMonitor p = pickMonitor(desk(), portrait());
  EXPECT_EQ(p.monitor, "HDMI-1");
  EXPECT_EQ(p.output, "HDMI-1");
  EXPECT_EQ(p.edidName, "LKG-P00671");
  EXPECT_EQ(p.rect, (Rect{1920, 0, 1536, 2048}));
  EXPECT_DOUBLE_EQ(p.refreshHz, 59.94);
  EXPECT_EQ(p.rule, "EDID LKG");
}

TEST(MonitorPicker, EdidBeatsAPlainMonitorOfTheSameSize) {
  RandrSnapshot s = desk();
  s.outputs.push_back(output("DP-2", "Other"));
  s.monitors.insert(s.monitors.begin(), monitor("DP-2", {-1536, 0, 1536, 2048}, {"DP-2"}));
  EXPECT_EQ(pickMonitor(s, portrait()).monitor, "HDMI-1");
}

TEST(MonitorPicker, SingleMonitorOfTheSizeWithoutEdid) {
  RandrSnapshot s = desk();
  s.outputs[1].edidMonitorName = "";
  PickedMonitor p = pickMonitor(s, portrait());
  EXPECT_EQ(p.monitor, "HDMI-1");
  EXPECT_EQ(p.rule, "size");
}

TEST(MonitorPicker, TwoPanelsOfTheSizeAreATie) {
  RandrSnapshot s = desk();
  s.outputs.push_back(output("HDMI-2", "LKG-P00999"));
  s.monitors.push_back(monitor("HDMI-2", {3456, 0, 1536, 2048}, {"HDMI-2"}));
  std::string e = errorOf(s, portrait());
  EXPECT_NE(e.find("several LKG monitors of 1536x2048"), std::string::npos) << e;
  EXPECT_NE(e.find("HDMI-1 1536x2048+1920+0"), std::string::npos) << e;
  EXPECT_NE(e.find("HDMI-2 1536x2048+3456+0"), std::string::npos) << e;
  // Naming one resolves the tie.
  PanelRequest byName = portrait();
  byName.output = "HDMI-2";
  EXPECT_EQ(pickMonitor(s, byName).monitor, "HDMI-2");
  PanelRequest byGeometry = portrait();
  byGeometry.geometry = parseGeometry("1536x2048+1920+0");
  EXPECT_EQ(pickMonitor(s, byGeometry).monitor, "HDMI-1");
}

TEST(MonitorPicker, TwoPlainMonitorsOfTheSizeAreATie) {
  RandrSnapshot s = desk();
  s.outputs[1].edidMonitorName = "";
  s.outputs.push_back(output("HDMI-2", ""));
  s.monitors.push_back(monitor("HDMI-2", {3456, 0, 1536, 2048}, {"HDMI-2"}));
  EXPECT_NE(errorOf(s, portrait()).find("several monitors of 1536x2048 and none with an LKG EDID"), std::string::npos);
}

TEST(MonitorPicker, RotatedPanelIsRefused) {
  RandrSnapshot s = desk();
  s.outputs[1].rotation = 2;  // Rotate_90
  std::string e = errorOf(s, portrait());
  EXPECT_NE(e.find("output HDMI-1 is rotated"), std::string::npos) << e;
  EXPECT_NE(e.find("--rotate normal"), std::string::npos) << e;
}

TEST(MonitorPicker, TransformedPanelIsRefused) {
  RandrSnapshot s = desk();
  s.outputs[1].identityTransform = false;
  EXPECT_NE(errorOf(s, portrait()).find("scaling transform"), std::string::npos);
}

TEST(MonitorPicker, PanelInTheWrongModeNamesWhatWasFound) {
  RandrSnapshot s = desk();
  s.monitors[1].rect = {1920, 0, 2048, 1536};  // landscape mode on a portrait panel
  std::string e = errorOf(s, portrait());
  EXPECT_NE(e.find("LKG monitor HDMI-1 2048x1536+1920+0 is not the calibration's 1536x2048"), std::string::npos) << e;
  EXPECT_NE(e.find("EDID 'LKG-P00671'"), std::string::npos) << e;
}

TEST(MonitorPicker, ExplicitNameOfTheWrongSizeIsRefused) {
  PanelRequest r = portrait();
  r.output = "DP-1";
  std::string e = errorOf(desk(), r);
  EXPECT_NE(e.find("monitor DP-1 (output name) is 1920x1080+0+0"), std::string::npos) << e;
  r.output = "VGA-7";
  EXPECT_NE(errorOf(desk(), r).find("no monitor or output named 'VGA-7'"), std::string::npos);
}

TEST(MonitorPicker, ExplicitNameMatchesMonitorOrOutput) {
  RandrSnapshot s;  // Xvfb: monitors made with `xrandr --setmonitor`, the EDID on output "screen"
  s.outputs = {output("screen", "LKG-P0001")};
  s.monitors = {monitor("MAIN", {0, 0, 1920, 1080}, {}), monitor("LKG-P", {1920, 0, 1536, 2048}, {"screen"})};
  PanelRequest r = portrait();
  r.output = "LKG-P";
  EXPECT_EQ(pickMonitor(s, r).rect, (Rect{1920, 0, 1536, 2048}));
  r.output = "screen";
  EXPECT_EQ(pickMonitor(s, r).monitor, "LKG-P");
  EXPECT_EQ(pickMonitor(s, portrait()).rule, "EDID LKG");
}

TEST(MonitorPicker, NothingFoundListsEveryMonitor) {
  RandrSnapshot s = desk();
  s.monitors.pop_back();
  std::string e = errorOf(s, portrait());
  EXPECT_NE(e.find("no monitor of 1536x2048 and none with an LKG EDID name"), std::string::npos) << e;
  EXPECT_NE(e.find("DP-1 1920x1080+0+0 (output DP-1, EDID 'DELL U2720Q')"), std::string::npos) << e;
  EXPECT_NE(errorOf(RandrSnapshot{}, portrait()).find("(none)"), std::string::npos);
}

TEST(MonitorPicker, GeometryParsing) {
  EXPECT_EQ(parseGeometry("96x128+160+0"), (Rect{160, 0, 96, 128}));
  EXPECT_EQ(parseGeometry("10x20-5+7"), (Rect{-5, 7, 10, 20}));
  EXPECT_THROW(parseGeometry("96x128"), PresentError);
  EXPECT_THROW(parseGeometry("0x128+0+0"), PresentError);
  EXPECT_EQ(describeRect({-5, 7, 10, 20}), "10x20-5+7");
}

}  // namespace
}  // namespace ht::present
