// panel_placement_test.cpp - the "panel" section of a display config (camera_models/panel_placement.h): parsing,
// the errors that name file, field, value and fix, and how it meets the monitor picker (a daemon-config / command-line
// choice wins; the section wins over the EDID rule).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "camera_models/display_config.h"
#include "common/error.h"
#include "present/monitor_picker.h"

namespace ht::present {
namespace {

// The tiny 96x128 panel config of the Xvfb tests with `panel` added (or the whole config replaced by `edit`).
nlohmann::json panelConfig(const nlohmann::json& panel) {
  std::ifstream in(std::string(HT_TEST_DATA_DIR) + "/configs/xvfb_panel_96x128.json");
  nlohmann::json config = nlohmann::json::parse(in);
  config["panel"] = panel;
  return config;
}

DisplayConfig parse(const nlohmann::json& config) { return parseDisplayConfig(config.dump(), "panel.json", {}); }

// The ConfigError's field, value and expectation, as "field | value | expected".
std::string errorOf(const nlohmann::json& config) {
  try {
    parse(config);
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "panel.json");
    return e.field() + " | " + e.value() + " | " + e.expected();
  }
  return "no error";
}

TEST(PanelPlacement, GeometryParsesAsXrandrPrintsIt) {
  EXPECT_EQ(parsePanelGeometry("1536x2048+1920+0"), (PanelGeometry{1920, 0, 1536, 2048}));
  EXPECT_EQ(parsePanelGeometry("10x20-5+7"), (PanelGeometry{-5, 7, 10, 20}));
  for (const char* bad : {"", "96x128", "96x128+0", "0x128+0+0", "96x0+0+0", "x128+0+0", "96x128+0+0 ", "123456x1+0+0"})
    EXPECT_FALSE(parsePanelGeometry(bad)) << bad;
}

TEST(PanelPlacement, OutputOrGeometryAreRead) {
  EXPECT_EQ(parse(panelConfig({{"output", "HDMI-1"}})).panel.output, "HDMI-1");
  const DisplayConfig g = parse(panelConfig({{"geometry", "96x128+160+0"}}));
  EXPECT_EQ(g.panel.geometry, (PanelGeometry{160, 0, 96, 128}));
  EXPECT_FALSE(g.panel.output);
  nlohmann::json none = panelConfig({});
  none.erase("panel");
  EXPECT_FALSE(parse(none).panel.output);
  EXPECT_FALSE(parse(none).panel.geometry);
}

TEST(PanelPlacement, BadValuesNameTheFieldTheValueAndTheFix) {
  EXPECT_EQ(errorOf(panelConfig({{"geometry", "96x128"}})),
            "panel.geometry | \"96x128\" | expected the panel's monitor as WIDTHxHEIGHT+X+Y (xrandr notation, e.g. "
            "\"1536x2048+1920+0\")");
  EXPECT_EQ(errorOf(panelConfig({{"geometry", "1536x2048+0+0"}})),
            "panel.geometry | \"1536x2048+0+0\" | expected the calibration's screen size 96x128 (the panel shows the "
            "frame 1:1), e.g. \"96x128+0+0\"");
  EXPECT_NE(errorOf(panelConfig({{"output", ""}})).find("panel.output | \"\" | expected a RandR output"),
            std::string::npos);
  EXPECT_NE(errorOf(panelConfig({{"output", 3}})).find("panel.output | 3 |"), std::string::npos);
  EXPECT_NE(errorOf(panelConfig({{"output", "HDMI-1"}, {"geometry", "96x128+0+0"}})).find("not both"),
            std::string::npos);
  EXPECT_NE(errorOf(panelConfig({{"monitor", "HDMI-1"}})).find("panel.monitor"), std::string::npos);
  EXPECT_NE(errorOf(panelConfig("HDMI-1")).find("panel | \"HDMI-1\" | expected a JSON object"), std::string::npos);
  nlohmann::json pinhole = panelConfig({{"output", "HDMI-1"}});
  pinhole["model"] = "pinhole";
  pinhole.erase("calibration");
  EXPECT_NE(errorOf(pinhole).find("expected no panel section unless model is \"lenticular\""), std::string::npos);
}

TEST(PanelPlacement, APlainVisualJsonStaysValid) {
  std::ifstream in(std::string(HT_TEST_DATA_DIR) + "/configs/xvfb_panel_96x128.json");
  const nlohmann::json visual = nlohmann::json::parse(in)["calibration"];
  const DisplayConfig c = parseDisplayConfig(visual.dump(), "visual.json", {});
  EXPECT_EQ(c.calibration->screenW, 96u);
  EXPECT_FALSE(c.panel.output || c.panel.geometry);
}

// Two monitors of the panel's size, the EDID LKG one at +160+0: the section's geometry picks the other one.
RandrSnapshot twoPanelSizedMonitors() {
  RandrSnapshot s;
  s.outputs.push_back({"DP-1", true, "LKG-P0001", "", {160, 0, 96, 128}, 96, 128, 60.0, 1, true});
  s.outputs.push_back({"DP-2", true, "", "", {0, 0, 96, 128}, 96, 128, 60.0, 1, true});
  s.monitors.push_back({"DP-1", {160, 0, 96, 128}, false, true, {"DP-1"}});
  s.monitors.push_back({"DP-2", {0, 0, 96, 128}, true, true, {"DP-2"}});
  return s;
}

TEST(PanelPlacement, TheSectionWinsOverTheEdidRuleAndTheCallersChoiceWinsOverIt) {
  const RandrSnapshot snapshot = twoPanelSizedMonitors();
  const PanelRequest plain{96, 128, std::nullopt, std::nullopt};
  EXPECT_EQ(pickMonitor(snapshot, plain).monitor, "DP-1");  // EDID LKG

  const DisplayConfig byGeometry = parse(panelConfig({{"geometry", "96x128+0+0"}}));
  const PickedMonitor g = pickMonitor(snapshot, withPlacement(plain, byGeometry.panel));
  EXPECT_EQ(g.monitor, "DP-2");
  EXPECT_EQ(g.rule, "geometry");

  const DisplayConfig byOutput = parse(panelConfig({{"output", "DP-2"}}));
  EXPECT_EQ(pickMonitor(snapshot, withPlacement(plain, byOutput.panel)).rule, "output name");

  PanelRequest daemonEntry = plain;  // a daemon-config entry naming DP-1 overrides the display's section
  daemonEntry.output = "DP-1";
  EXPECT_EQ(pickMonitor(snapshot, withPlacement(daemonEntry, byGeometry.panel)).monitor, "DP-1");
}

}  // namespace
}  // namespace ht::present
