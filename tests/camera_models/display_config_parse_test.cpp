// Parsing of good inputs: every visual.json fixture of docs/OPTICS.md §1.1, both CellPatternMode casings, bare vs
// wrapped numbers, booleans, flips, our display-config format, and the built-in (embedded) displays.
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "camera_models/display_config.h"
#include "camera_models/looking_glass_calibration.h"
#include "camera_test_support.h"
#include "common/error.h"

namespace ht {
namespace {

using test::fixturePath;
using test::loadFixture;

TEST(DisplayConfigParse, PortraitPr56WrappedVersion3) {
  DisplayConfig config = loadFixture("portrait_pr56_visual.json");
  ASSERT_TRUE(config.calibration);
  const LookingGlassCalibration& c = *config.calibration;
  EXPECT_EQ(config.model, DisplayModel::Lenticular);
  EXPECT_EQ(config.name, "LKG-PORT-");
  EXPECT_EQ(config.sourcePath, fixturePath("portrait_pr56_visual.json"));
  EXPECT_EQ(c.configVersion, "3.0");
  EXPECT_DOUBLE_EQ(c.pitch, 52.594383239746094);
  EXPECT_DOUBLE_EQ(c.slope, -7.21152925491333);
  EXPECT_DOUBLE_EQ(c.center, 0.40277382731437683);
  EXPECT_DOUBLE_EQ(c.viewCone, 40.0);
  EXPECT_TRUE(c.invView);
  EXPECT_DOUBLE_EQ(c.DPI, 324.0);
  EXPECT_EQ(c.screenW, 1536u);
  EXPECT_EQ(c.screenH, 2048u);
  EXPECT_FALSE(c.flipImageX);
  EXPECT_FALSE(c.flipImageY);
  EXPECT_FALSE(c.flipSubp);
  EXPECT_EQ(c.cellPatternMode, 0);
  EXPECT_TRUE(c.subpixelCells.empty());
  EXPECT_DOUBLE_EQ(c.fringe, 0.0);  // absent -> default 0 (Bridge displays.ts)
  EXPECT_EQ(config.spp, 4u);
  EXPECT_FALSE(config.camera.target);
  EXPECT_FALSE(config.camera.size);
  EXPECT_DOUBLE_EQ(config.camera.fovyDeg, 14.0);
  EXPECT_DOUBLE_EQ(config.camera.depthiness, 1.0);
}

TEST(DisplayConfigParse, PortraitIssue3Version1) {
  LookingGlassCalibration c = loadLookingGlassCalibration(fixturePath("portrait_issue3_visual.json"));
  EXPECT_EQ(c.configVersion, "1.0");
  EXPECT_EQ(c.serial, "LKG-PORT-02283");
  EXPECT_DOUBLE_EQ(c.pitch, 52.563010659943416);
  EXPECT_DOUBLE_EQ(c.slope, -7.244674277559994);
  EXPECT_DOUBLE_EQ(c.center, 0.4016996953176948);
  EXPECT_DOUBLE_EQ(c.fringe, 0.0);
  EXPECT_EQ(c.cellPatternMode, 0);  // version 1.0 files have no CellPatternMode
}

TEST(DisplayConfigParse, Gen1OriginalPositiveSlope) {
  LookingGlassCalibration c = loadLookingGlassCalibration(fixturePath("gen1_8.9_original_visual.json"));
  EXPECT_DOUBLE_EQ(c.pitch, 49.825218200683597);
  EXPECT_DOUBLE_EQ(c.slope, 5.2160325050354);
  EXPECT_DOUBLE_EQ(c.center, -0.23396748304367066);
  EXPECT_EQ(c.screenW, 2560u);
  EXPECT_EQ(c.screenH, 1600u);
  EXPECT_DOUBLE_EQ(c.DPI, 338.0);
}

TEST(DisplayConfigParse, BareNumbersAndTrueFalseBooleans) {
  LookingGlassCalibration c = loadLookingGlassCalibration(fixturePath("gen1_8.9_user_bare_visual.json"));
  EXPECT_DOUBLE_EQ(c.pitch, 47.56401443481445);
  EXPECT_DOUBLE_EQ(c.slope, -5.480000019073486);
  EXPECT_DOUBLE_EQ(c.center, 0.374184787273407);
  EXPECT_TRUE(c.invView);
  EXPECT_FALSE(c.flipImageX);
}

TEST(DisplayConfigParse, BareAndWrappedNumbersAgree) {
  const std::string wrapped = R"({"pitch":{"value":52.5},"slope":{"value":-7.2},"center":{"value":0.4},
    "viewCone":{"value":40},"invView":{"value":1},"DPI":{"value":324},"screenW":{"value":1536.0},
    "screenH":{"value":2048},"flipImageX":{"value":0},"flipImageY":{"value":1},"flipSubp":{"value":true},
    "fringe":{"value":0.25},"CellPatternMode":{"value":0}})";
  const std::string bare = R"({"pitch":52.5,"slope":-7.2,"center":0.4,"viewCone":40,"invView":true,"DPI":324,
    "screenW":1536,"screenH":2048.0,"flipImageX":false,"flipImageY":1,"flipSubp":1,"fringe":0.25,"CellPatternMode":0})";
  LookingGlassCalibration a = parseLookingGlassCalibrationText(wrapped, "wrapped.json");
  LookingGlassCalibration b = parseLookingGlassCalibrationText(bare, "bare.json");
  for (const LookingGlassCalibration* c : {&a, &b}) {
    EXPECT_DOUBLE_EQ(c->pitch, 52.5);
    EXPECT_DOUBLE_EQ(c->slope, -7.2);
    EXPECT_DOUBLE_EQ(c->center, 0.4);
    EXPECT_DOUBLE_EQ(c->viewCone, 40.0);
    EXPECT_TRUE(c->invView);
    EXPECT_EQ(c->screenW, 1536u);
    EXPECT_EQ(c->screenH, 2048u);
    EXPECT_FALSE(c->flipImageX);
    EXPECT_TRUE(c->flipImageY);
    EXPECT_TRUE(c->flipSubp);
    EXPECT_DOUBLE_EQ(c->fringe, 0.25);
  }
}

TEST(DisplayConfigParse, Gen3LandscapeCapitalCellPatternMode) {
  LookingGlassCalibration c = loadLookingGlassCalibration(fixturePath("gen3_16_landscape_visual.json"));
  EXPECT_EQ(c.cellPatternMode, 2);
  ASSERT_EQ(c.subpixelCells.size(), 2u);
  EXPECT_DOUBLE_EQ(c.subpixelCells[0].ROffsetX, -0.31);
  EXPECT_DOUBLE_EQ(c.subpixelCells[0].GOffsetX, 0.28);
  EXPECT_DOUBLE_EQ(c.subpixelCells[0].BOffsetY, -0.25);
  EXPECT_DOUBLE_EQ(c.subpixelCells[1].ROffsetY, -0.25);
  EXPECT_DOUBLE_EQ(c.subpixelCells[1].BOffsetY, 0.25);
  EXPECT_EQ(c.subpixelCells[1].offset(2), glm::dvec2(0.0, 0.25));
}

TEST(DisplayConfigParse, Gen3PortraitLowercaseCellPatternMode) {
  LookingGlassCalibration c = loadLookingGlassCalibration(fixturePath("gen3_16_portrait_lowercase_visual.json"));
  EXPECT_EQ(c.cellPatternMode, 4);
  ASSERT_EQ(c.subpixelCells.size(), 2u);
  EXPECT_DOUBLE_EQ(c.subpixelCells[1].ROffsetX, 0.25);
  EXPECT_DOUBLE_EQ(c.subpixelCells[1].GOffsetY, 0.28);
  EXPECT_EQ(c.screenW, 2160u);
  EXPECT_EQ(c.screenH, 3840u);
}

TEST(DisplayConfigParse, FlipsAndFlipSubp) {
  LookingGlassCalibration c = parseLookingGlassCalibrationText(
      R"({"pitch":50,"slope":-7,"center":0,"viewCone":40,"invView":0,"DPI":300,"screenW":100,"screenH":200,
          "flipImageX":true,"flipImageY":{"value":1.0},"flipSubp":{"value":true}})",
      "flips.json");
  EXPECT_FALSE(c.invView);
  EXPECT_TRUE(c.flipImageX);
  EXPECT_TRUE(c.flipImageY);
  EXPECT_TRUE(c.flipSubp);
}

TEST(DisplayConfigParse, UnknownVisualJsonKeysKeptVerbatim) {
  const std::string text = R"({"pitch":50,"slope":-7,"center":0,"viewCone":40,"invView":1,"DPI":300,
      "screenW":100,"screenH":200,"flipImageX":0,"flipImageY":0,"flipSubp":0,
      "quiltSettings":{"columns":8,"rows":6},"futureField":{"value":3.5}})";
  DisplayConfig config = parseDisplayConfig(text, "future.json", "");
  ASSERT_TRUE(config.calibration);
  const nlohmann::json kept = nlohmann::json::parse(config.calibration->rawJson);
  EXPECT_EQ(kept["quiltSettings"]["columns"], 8);
  EXPECT_EQ(kept["futureField"]["value"], 3.5);
  EXPECT_EQ(kept, nlohmann::json::parse(text));
}

TEST(DisplayConfigParse, OurFormatWithCalibrationPath) {
  DisplayConfig config = loadFixture("display_portrait_by_path.json");
  EXPECT_EQ(config.name, "my-portrait");
  EXPECT_EQ(config.model, DisplayModel::Lenticular);
  ASSERT_TRUE(config.calibration);
  EXPECT_DOUBLE_EQ(config.calibration->pitch, 52.594383239746094);
  ASSERT_TRUE(config.camera.target);
  EXPECT_EQ(*config.camera.target, glm::dvec3(0.0, 0.5, -1.0));
  ASSERT_TRUE(config.camera.size);
  EXPECT_DOUBLE_EQ(*config.camera.size, 1.5);
  EXPECT_DOUBLE_EQ(config.camera.fovyDeg, 16.0);
  EXPECT_DOUBLE_EQ(config.camera.depthiness, 1.25);
  EXPECT_EQ(config.spp, 8u);
}

TEST(DisplayConfigParse, OurFormatPinhole) {
  DisplayConfig config = loadFixture("display_pinhole.json");
  EXPECT_EQ(config.model, DisplayModel::Pinhole);
  EXPECT_FALSE(config.calibration);
  EXPECT_EQ(config.pinhole.width, 640u);
  EXPECT_EQ(config.pinhole.height, 480u);
  EXPECT_EQ(config.pinhole.fovyDeg, 50.0);
  EXPECT_EQ(config.pinhole.eye, glm::dvec3(0, 1, 5));
  EXPECT_EQ(config.pinhole.lookAt, glm::dvec3(0, 1, 0));
  EXPECT_EQ(config.spp, 2u);
}

TEST(DisplayConfigParse, EmbeddedCalibrationAndAutoKeywords) {
  DisplayConfig config = parseDisplayConfig(
      R"({"name":"x","calibration":{"pitch":50,"slope":-7,"center":0,"viewCone":40,"invView":1,"DPI":300,
          "screenW":100,"screenH":200,"flipImageX":0,"flipImageY":0,"flipSubp":0},
          "camera":{"target":"auto","size":"auto"}})",
      "inline.json", "");
  EXPECT_FALSE(config.camera.target);
  EXPECT_FALSE(config.camera.size);
  EXPECT_EQ(config.calibration->screenH, 200u);
}

TEST(DisplayConfigBuiltin, NamesAndNominalValues) {
  EXPECT_EQ(builtinDisplayNames(),
            (std::vector<std::string>{"capture-16x16", "capture-8x6", "gen1-8.9", "gen3-16-landscape", "go",
                                      "holovizio-wall-70", "integral-15-4k", "oblique-9x9", "portrait"}));
  for (const std::string& name : builtinDisplayNames()) {
    DisplayConfig config = builtinDisplay(name);
    EXPECT_EQ(config.name, name);
    EXPECT_EQ(config.sourcePath, "builtin:" + name);
    EXPECT_EQ(config.spp, 4u) << name;
    ASSERT_EQ(config.calibration.has_value(), config.model == DisplayModel::Lenticular) << name;
  }
  // Portrait = the real PR #56 file; 16" Gen3 = LKG-J template; 8.9" = driverless-HoloPlay.js "original calibration".
  LookingGlassCalibration pr56 = loadLookingGlassCalibration(fixturePath("portrait_pr56_visual.json"));
  LookingGlassCalibration portrait = *builtinDisplay("portrait").calibration;
  EXPECT_EQ(portrait.pitch, pr56.pitch);
  EXPECT_EQ(portrait.slope, pr56.slope);
  EXPECT_EQ(portrait.center, pr56.center);
  EXPECT_EQ(portrait.DPI, pr56.DPI);
  EXPECT_EQ(portrait.invView, pr56.invView);
  LookingGlassCalibration gen3 = *builtinDisplay("gen3-16-landscape").calibration;
  LookingGlassCalibration lkgJ = loadLookingGlassCalibration(fixturePath("gen3_16_landscape_visual.json"));
  EXPECT_EQ(gen3.cellPatternMode, 2);
  ASSERT_EQ(gen3.subpixelCells.size(), 2u);
  for (std::uint32_t k = 0; k < 2; ++k)
    for (std::uint32_t c = 0; c < 3; ++c) EXPECT_EQ(gen3.subpixelCells[k].offset(c), lkgJ.subpixelCells[k].offset(c));
  EXPECT_EQ(gen3.pitch, 44.72);
  EXPECT_EQ(gen3.viewCone, 50.0);
  LookingGlassCalibration gen1 = *builtinDisplay("gen1-8.9").calibration;
  LookingGlassCalibration original = loadLookingGlassCalibration(fixturePath("gen1_8.9_original_visual.json"));
  EXPECT_EQ(gen1.pitch, original.pitch);
  EXPECT_EQ(gen1.slope, original.slope);
  EXPECT_EQ(gen1.center, original.center);
}

TEST(DisplayConfigBuiltin, EmbeddedCopiesMatchShippedFiles) {
  for (const std::string& name : builtinDisplayNames()) {
    DisplayConfig fromDisk = loadDisplayConfig(std::string(HT_SOURCE_DIR "/configs/") + name + ".json");
    DisplayConfig embedded = builtinDisplay(name);
    ASSERT_EQ(fromDisk.calibration.has_value(), embedded.calibration.has_value()) << name;
    if (fromDisk.calibration) { EXPECT_EQ(fromDisk.calibration->rawJson, embedded.calibration->rawJson) << name; }
    EXPECT_EQ(fromDisk.description, embedded.description) << name;
  }
}

TEST(DisplayConfigBuiltin, ResolveDisplaySpecs) {
  EXPECT_EQ(resolveDisplay("builtin:portrait").name, "portrait");
  EXPECT_EQ(resolveDisplay(fixturePath("display_pinhole.json")).name, "preview");
  EXPECT_THROW(resolveDisplay("builtin:nope"), ConfigError);
}

// The stop rule of progressive streams on a display (docs/SERVICE.md §4.1): optional, checked like every field.
TEST(DisplayConfigParse, ProgressiveStopRule) {
  const std::string base = R"({"model":"pinhole","pinhole":{"width":64,"height":48})";
  const DisplayConfig none = parseDisplayConfig(base + "}", "p.json", {});
  EXPECT_FALSE(none.progressiveTargetError.has_value());
  EXPECT_FALSE(none.progressiveMaxSpp.has_value());
  const DisplayConfig set =
      parseDisplayConfig(base + R"(,"progressive":{"target_error":0.01,"max_spp":512}})", "p.json", {});
  EXPECT_EQ(set.progressiveTargetError.value_or(0.0), 0.01);
  EXPECT_EQ(set.progressiveMaxSpp.value_or(0u), 512u);
  for (const char* bad : {R"(,"progressive":{"target_error":-1}})", R"(,"progressive":{"max_spp":0}})",
                          R"(,"progressive":{"maxSpp":8}})", R"(,"progressive":3})"}) {
    SCOPED_TRACE(bad);
    EXPECT_THROW(parseDisplayConfig(base + bad, "p.json", {}), ConfigError);
  }
  try {
    parseDisplayConfig(base + R"(,"progressive":{"target_error":-1}})", "p.json", {});
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("progressive.target_error"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ht
