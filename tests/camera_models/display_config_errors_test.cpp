// Bad inputs, one test each: every error is a ConfigError naming the file, the field, the value as written and the
// allowed range (common/error.h).
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/looking_glass_calibration.h"
#include "camera_test_support.h"
#include "common/error.h"

namespace ht {
namespace {

using test::fixturePath;
using ::testing::HasSubstr;

// A valid visual.json with one field replaced (or removed when replacement is empty).
std::string visualJsonWith(const std::string& key, const std::string& replacement) {
  nlohmann::json j = nlohmann::json::parse(R"({"configVersion":"3.0","serial":"LKG-P","pitch":{"value":52},
      "slope":{"value":-7},"center":{"value":0.5},"viewCone":{"value":40},"invView":{"value":1},
      "verticalAngle":{"value":0},"DPI":{"value":324},"screenW":{"value":1536},"screenH":{"value":2048},
      "flipImageX":{"value":0},"flipImageY":{"value":0},"flipSubp":{"value":0},"CellPatternMode":{"value":0},
      "subpixelCells":[]})");
  if (replacement.empty()) {
    j.erase(key);
  } else {
    j[key] = nlohmann::json::parse(replacement);
  }
  return j.dump();
}

ConfigError catchConfigError(const std::function<void()>& action) {
  try {
    action();
  } catch (const ConfigError& e) { return e; }
  ADD_FAILURE() << "expected a ConfigError";
  return ConfigError("", "", "", "");
}

ConfigError visualJsonError(const std::string& key, const std::string& replacement) {
  return catchConfigError([&] { parseDisplayConfig(visualJsonWith(key, replacement), "visual.json", ""); });
}

TEST(DisplayConfigErrors, MissingField) {
  ConfigError e = visualJsonError("pitch", "");
  EXPECT_EQ(e.file(), "visual.json");
  EXPECT_EQ(e.field(), "pitch");
  EXPECT_EQ(e.value(), "(missing)");
  EXPECT_THAT(e.expected(), HasSubstr("> 0"));
  EXPECT_THAT(e.expected(), HasSubstr("required"));
  EXPECT_THAT(std::string(e.what()), HasSubstr("visual.json: field 'pitch'"));
}

TEST(DisplayConfigErrors, StringValue) {
  ConfigError e = visualJsonError("center", R"({"value":"0.5"})");
  EXPECT_EQ(e.field(), "center");
  EXPECT_EQ(e.value(), R"({"value":"0.5"})");
  EXPECT_THAT(e.expected(), HasSubstr("finite number"));
}

TEST(DisplayConfigErrors, NaNWrittenAsString) {
  ConfigError e = visualJsonError("slope", R"("NaN")");
  EXPECT_EQ(e.field(), "slope");
  EXPECT_EQ(e.value(), R"("NaN")");
  EXPECT_THAT(e.expected(), HasSubstr("finite non-zero number"));
}

TEST(DisplayConfigErrors, NumberOverflow) {
  ConfigError e = catchConfigError([] { parseDisplayConfig(R"({"pitch": 1e999})", "huge.json", ""); });
  EXPECT_EQ(e.file(), "huge.json");
  EXPECT_EQ(e.field(), "(json)");
  EXPECT_THAT(e.expected(), HasSubstr("finite numbers"));
}

TEST(DisplayConfigErrors, PitchNotPositive) {
  for (const char* value : {"0", "-52"}) {
    ConfigError e = visualJsonError("pitch", std::string(R"({"value":)") + value + "}");
    EXPECT_EQ(e.field(), "pitch");
    EXPECT_EQ(e.value(), std::string(R"({"value":)") + value + "}");
    EXPECT_THAT(e.expected(), HasSubstr("> 0"));
  }
}

TEST(DisplayConfigErrors, SlopeZero) {
  ConfigError e = visualJsonError("slope", R"({"value":0.0})");
  EXPECT_EQ(e.field(), "slope");
  EXPECT_EQ(e.value(), R"({"value":0.0})");
  EXPECT_THAT(e.expected(), HasSubstr("non-zero"));
}

TEST(DisplayConfigErrors, ScreenWidthZero) {
  ConfigError e = visualJsonError("screenW", "0");
  EXPECT_EQ(e.field(), "screenW");
  EXPECT_EQ(e.value(), "0");
  EXPECT_THAT(e.expected(), HasSubstr("[1, 32768]"));
}

TEST(DisplayConfigErrors, ScreenWidthTooLarge) {
  ConfigError e = visualJsonError("screenW", R"({"value":100000})");
  EXPECT_EQ(e.field(), "screenW");
  EXPECT_EQ(e.value(), R"({"value":100000})");
  EXPECT_THAT(e.expected(), HasSubstr("[1, 32768]"));
}

TEST(DisplayConfigErrors, ScreenHeightNotInteger) {
  ConfigError e = visualJsonError("screenH", "2048.5");
  EXPECT_EQ(e.field(), "screenH");
  EXPECT_THAT(e.expected(), HasSubstr("integer"));
}

TEST(DisplayConfigErrors, ViewConeOutOfRange) {
  ConfigError e = visualJsonError("viewCone", R"({"value":180})");
  EXPECT_EQ(e.field(), "viewCone");
  EXPECT_THAT(e.expected(), HasSubstr("(0, 180)"));
}

TEST(DisplayConfigErrors, DpiNotPositive) {
  ConfigError e = visualJsonError("DPI", R"({"value":-1})");
  EXPECT_EQ(e.field(), "DPI");
  EXPECT_THAT(e.expected(), HasSubstr("> 0"));
}

TEST(DisplayConfigErrors, BooleanNotZeroOrOne) {
  ConfigError e = visualJsonError("invView", R"({"value":2})");
  EXPECT_EQ(e.field(), "invView");
  EXPECT_THAT(e.expected(), HasSubstr("0, 1, true or false"));
}

TEST(DisplayConfigErrors, CellPatternModeSeven) {
  ConfigError e = visualJsonError("CellPatternMode", R"({"value":7})");
  EXPECT_EQ(e.field(), "CellPatternMode");
  EXPECT_EQ(e.value(), R"({"value":7})");
  EXPECT_THAT(e.expected(), HasSubstr("[0, 4]"));
}

TEST(DisplayConfigErrors, LowercaseCellPatternModeSeven) {
  std::string text = visualJsonWith("CellPatternMode", "");
  text.insert(1, R"("cellPatternMode": 7,)");
  ConfigError e = catchConfigError([&] { parseDisplayConfig(text, "visual.json", ""); });
  EXPECT_EQ(e.field(), "cellPatternMode");
  EXPECT_THAT(e.expected(), HasSubstr("[0, 4]"));
}

TEST(DisplayConfigErrors, TooManyCells) {
  const std::string cell = R"({"ROffsetX":0,"ROffsetY":0,"GOffsetX":0,"GOffsetY":0,"BOffsetX":0,"BOffsetY":0})";
  const std::string fiveCells = "[" + cell + "," + cell + "," + cell + "," + cell + "," + cell + "]";
  std::string text = visualJsonWith("subpixelCells", fiveCells);
  ConfigError e = catchConfigError([&] { parseDisplayConfig(text, "visual.json", ""); });
  EXPECT_EQ(e.field(), "subpixelCells");
  EXPECT_THAT(e.expected(), HasSubstr("at most 4"));
  EXPECT_THAT(e.expected(), HasSubstr("got 5"));
}

TEST(DisplayConfigErrors, CellModeWithoutCells) {
  ConfigError e = visualJsonError("CellPatternMode", R"({"value":2})");
  EXPECT_EQ(e.field(), "subpixelCells");
  EXPECT_THAT(e.expected(), HasSubstr("1 to 4 cells"));
}

TEST(DisplayConfigErrors, CellOffsetTooLarge) {
  std::string text = visualJsonWith(
      "subpixelCells", R"([{"ROffsetX":0,"ROffsetY":0,"GOffsetX":2.5,"GOffsetY":0,"BOffsetX":0,"BOffsetY":0}])");
  ConfigError e = catchConfigError([&] { parseDisplayConfig(text, "visual.json", ""); });
  EXPECT_EQ(e.field(), "subpixelCells[0].GOffsetX");
  EXPECT_EQ(e.value(), "2.5");
  EXPECT_THAT(e.expected(), HasSubstr("[-2, 2]"));
}

TEST(DisplayConfigErrors, EmbeddedCalibrationFieldPath) {
  std::string text = R"({"name":"x","calibration":)" + visualJsonWith("slope", "0") + "}";
  ConfigError e = catchConfigError([&] { parseDisplayConfig(text, "display.json", ""); });
  EXPECT_EQ(e.file(), "display.json");
  EXPECT_EQ(e.field(), "calibration.slope");
  EXPECT_EQ(e.value(), "0");
}

TEST(DisplayConfigErrors, UnknownKeyInOurFormat) {
  std::string text = R"({"name":"x","calibration":)" + visualJsonWith("fringe", "0") + R"(,"camera":{"fovy":14}})";
  ConfigError e = catchConfigError([&] { parseDisplayConfig(text, "display.json", ""); });
  EXPECT_EQ(e.file(), "display.json");
  EXPECT_EQ(e.field(), "camera.fovy");
  EXPECT_EQ(e.value(), "14");
  EXPECT_THAT(e.expected(), HasSubstr("fovyDeg"));
}

TEST(DisplayConfigErrors, UnknownTopLevelKeyInOurFormat) {
  ConfigError e = catchConfigError([] { parseDisplayConfig(R"({"name":"x","sppp":4})", "display.json", ""); });
  EXPECT_EQ(e.field(), "sppp");
  EXPECT_THAT(e.expected(), HasSubstr("spp"));
}

TEST(DisplayConfigErrors, MalformedJsonWithLineAndColumn) {
  const std::string text = "{\n  \"name\": \"x\",\n  \"spp\": 4,,\n}\n";
  ConfigError e = catchConfigError([&] { parseDisplayConfig(text, "broken.json", ""); });
  EXPECT_EQ(e.file(), "broken.json");
  EXPECT_EQ(e.field(), "(json)");
  EXPECT_EQ(e.value(), "line 3, column 12");  // the second comma
  EXPECT_THAT(e.expected(), HasSubstr("valid JSON"));
}

TEST(DisplayConfigErrors, MissingCalibrationFile) {
  ConfigError e = catchConfigError([] { loadDisplayConfig(fixturePath("display_missing_calibration.json")); });
  EXPECT_EQ(e.file(), fixturePath("display_missing_calibration.json"));
  EXPECT_EQ(e.field(), "calibration");
  EXPECT_EQ(e.value(), "\"" + fixturePath("no_such_dir/visual.json") + "\"");
  EXPECT_THAT(e.expected(), HasSubstr("relative to the config file"));
}

TEST(DisplayConfigErrors, MissingConfigFile) {
  ConfigError e = catchConfigError([] { loadDisplayConfig(fixturePath("does_not_exist.json")); });
  EXPECT_EQ(e.file(), fixturePath("does_not_exist.json"));
  EXPECT_EQ(e.field(), "(file)");
  EXPECT_THAT(e.expected(), HasSubstr("existing, readable"));
}

TEST(DisplayConfigErrors, LenticularWithoutCalibration) {
  ConfigError e = catchConfigError([] { parseDisplayConfig(R"({"name":"x"})", "display.json", ""); });
  EXPECT_EQ(e.field(), "calibration");
  EXPECT_EQ(e.value(), "(missing)");
  EXPECT_THAT(e.expected(), HasSubstr("required for model \"lenticular\""));
}

TEST(DisplayConfigErrors, UnknownModel) {
  ConfigError e = catchConfigError([] { parseDisplayConfig(R"({"model":"holovizio"})", "display.json", ""); });
  EXPECT_EQ(e.field(), "model");
  EXPECT_EQ(e.value(), "\"holovizio\"");
  EXPECT_THAT(e.expected(), HasSubstr("\"lenticular\" or \"pinhole\""));
}

TEST(DisplayConfigErrors, DepthinessMakesConeTooWide) {
  std::string text = R"({"calibration":)" + visualJsonWith("fringe", "0") + R"(,"camera":{"depthiness":4.5}})";
  ConfigError e = catchConfigError([&] { parseDisplayConfig(text, "display.json", ""); });
  EXPECT_EQ(e.field(), "camera.depthiness");
  EXPECT_EQ(e.value(), "4.5");
  EXPECT_THAT(e.expected(), HasSubstr("< 180"));
}

TEST(DisplayConfigErrors, SizeNotPositive) {
  std::string text = R"({"calibration":)" + visualJsonWith("fringe", "0") + R"(,"camera":{"size":-1}})";
  ConfigError e = catchConfigError([&] { parseDisplayConfig(text, "display.json", ""); });
  EXPECT_EQ(e.field(), "camera.size");
  EXPECT_THAT(e.expected(), HasSubstr("\"auto\""));
}

TEST(DisplayConfigErrors, SppOutOfRange) {
  std::string text = R"({"calibration":)" + visualJsonWith("fringe", "0") + R"(,"spp":0})";
  ConfigError e = catchConfigError([&] { parseDisplayConfig(text, "display.json", ""); });
  EXPECT_EQ(e.field(), "spp");
  EXPECT_THAT(e.expected(), HasSubstr("[1, 4096]"));
}

TEST(DisplayConfigErrors, TargetNotAPoint) {
  std::string text = R"({"calibration":)" + visualJsonWith("fringe", "0") + R"(,"camera":{"target":[1,2]}})";
  ConfigError e = catchConfigError([&] { parseDisplayConfig(text, "display.json", ""); });
  EXPECT_EQ(e.field(), "camera.target");
  EXPECT_EQ(e.value(), "[1,2]");
  EXPECT_THAT(e.expected(), HasSubstr("[x, y, z]"));
}

TEST(DisplayConfigErrors, UnknownBuiltin) {
  ConfigError e = catchConfigError([] { builtinDisplay("lkg-65"); });
  EXPECT_EQ(e.file(), "builtin:lkg-65");
  EXPECT_EQ(e.value(), "\"lkg-65\"");
  EXPECT_THAT(e.expected(), HasSubstr("portrait"));
}

TEST(DisplayConfigErrors, LenticularParamsFromPinholeConfig) {
  DisplayConfig config = test::loadFixture("display_pinhole.json");
  ConfigError e = catchConfigError([&] { makeLenticularParams(config, test::testBounds()); });
  EXPECT_EQ(e.field(), "model");
  EXPECT_EQ(e.value(), "\"pinhole\"");
}

TEST(DisplayConfigErrors, PinholeUpParallelToView) {
  DisplayConfig config = parseDisplayConfig(
      R"({"model":"pinhole","pinhole":{"eye":[0,5,0],"lookAt":[0,0,0],"up":[0,1,0]}})", "pinhole.json", "");
  ConfigError e = catchConfigError([&] { makePinholeParams(config, test::testBounds()); });
  EXPECT_EQ(e.field(), "pinhole.up");
  EXPECT_THAT(e.expected(), HasSubstr("not parallel"));
}

}  // namespace
}  // namespace ht
