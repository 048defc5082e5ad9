// The "projectorArray" section (model "projector-array", docs/configs.md): a valid section parses field by field, and
// every bad value is a ConfigError naming the field (projector in front of the screen, zero / negative sizes,
// non-finite numbers, singular or wrapping homographies, unknown keys, a section without the model or vice versa).
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "camera_models/display_config.h"
#include "camera_models/projector_setup.h"
#include "camera_test_support.h"
#include "common/error.h"

namespace ht {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

json validConfig() {
  return json::parse(R"({"name": "pa", "model": "projector-array",
      "projectorArray": {"screen": {"width": 800, "height": 600}, "observerDistance": 2500, "observerHeight": 150,
                         "angularScattering": 0.02, "image": {"width": 640, "height": 480},
                         "projectors": [{"position": [-100, 0, -1500]},
                                        {"position": [100, 0, -1500], "width": 320, "height": 240}]}})");
}

ConfigError errorOf(const json& config) {
  try {
    parseDisplayConfig(config.dump(), "pa.json", "");
  } catch (const ConfigError& e) { return e; }
  ADD_FAILURE() << "expected a ConfigError for " << config.dump();
  return ConfigError("", "", "", "");
}

// The config with `edit` applied to its projectorArray section.
ConfigError projectorSectionError(const std::function<void(json&)>& edit) {
  json config = validConfig();
  edit(config["projectorArray"]);
  return errorOf(config);
}

TEST(ProjectorConfig, ParsesSection) {
  const DisplayConfig config = parseDisplayConfig(validConfig().dump(), "pa.json", "");
  EXPECT_EQ(config.model, DisplayModel::ProjectorArray);
  EXPECT_EQ(displayModelName(config.model), "projector-array");
  ASSERT_TRUE(config.projectorArray.has_value());
  const ProjectorArrayConfig& a = *config.projectorArray;
  EXPECT_EQ(a.screenWidth, 800.0);
  EXPECT_EQ(a.observerDistance, 2500.0);
  EXPECT_EQ(a.observerHeight, 150.0);
  EXPECT_EQ(*a.angularScattering, 0.02);
  ASSERT_EQ(a.projectors.size(), 2u);
  EXPECT_EQ(a.projectors[0].width, 640u);   // from "image"
  EXPECT_EQ(a.projectors[1].height, 240u);  // its own
  EXPECT_EQ(a.projectors[0].position, glm::dvec3(-100, 0, -1500));
  EXPECT_FALSE(a.projectors[0].homography.has_value());
}

TEST(ProjectorConfig, ShippedWallAndFixtureLoad) {
  const DisplayConfig wall = builtinDisplay("holovizio-wall-70");
  ASSERT_TRUE(wall.projectorArray.has_value());
  EXPECT_EQ(wall.projectorArray->projectors.size(), 70u);
  const DisplayConfig small = test::loadFixture("display_projector_small.json");
  ASSERT_TRUE(small.projectorArray->projectors[3].homography.has_value());
  EXPECT_EQ((*small.projectorArray->projectors[3].homography)[0], 1.3);
}

TEST(ProjectorConfig, ProjectorInFrontOfScreen) {
  for (double z : {0.0, 10.0}) {
    ConfigError e = projectorSectionError([&](json& s) { s["projectors"][1]["position"] = {0, 0, z}; });
    EXPECT_EQ(e.field(), "projectorArray.projectors[1].position");
    EXPECT_THAT(e.expected(), HasSubstr("z < 0"));
  }
}

TEST(ProjectorConfig, ZeroOrNegativeSizes) {
  EXPECT_EQ(projectorSectionError([](json& s) { s["screen"]["width"] = 0; }).field(), "projectorArray.screen.width");
  EXPECT_EQ(projectorSectionError([](json& s) { s["screen"]["height"] = -600; }).field(),
            "projectorArray.screen.height");
  EXPECT_EQ(projectorSectionError([](json& s) { s["observerDistance"] = 0; }).field(),
            "projectorArray.observerDistance");
  EXPECT_EQ(projectorSectionError([](json& s) { s["observerDistance"] = -1; }).field(),
            "projectorArray.observerDistance");
  EXPECT_EQ(projectorSectionError([](json& s) { s["image"]["width"] = 0; }).field(), "projectorArray.image.width");
  EXPECT_EQ(projectorSectionError([](json& s) { s["projectors"][1]["height"] = 0; }).field(),
            "projectorArray.projectors[1].height");
  EXPECT_EQ(projectorSectionError([](json& s) { s["angularScattering"] = -0.1; }).field(),
            "projectorArray.angularScattering");
  EXPECT_EQ(projectorSectionError([](json& s) { s["projectors"] = json::array(); }).field(),
            "projectorArray.projectors");
}

TEST(ProjectorConfig, NonFiniteNumbers) {
  // JSON has no NaN literal: a NaN arrives as a string or an overflowing number.
  EXPECT_EQ(projectorSectionError([](json& s) { s["observerDistance"] = "NaN"; }).field(),
            "projectorArray.observerDistance");
  EXPECT_EQ(projectorSectionError([](json& s) { s["observerHeight"] = std::nan(""); }).field(),
            "projectorArray.observerHeight");  // dumps as null
  EXPECT_EQ(projectorSectionError([](json& s) {
              s["projectors"][0]["position"] = {0, "NaN", -10};
            }).field(),
            "projectorArray.projectors[0].position");
  json config = validConfig();
  std::string text = config.dump();
  text.replace(text.find("2500"), 4, "1e999");
  EXPECT_THROW(parseDisplayConfig(text, "pa.json", ""), ConfigError);
}

TEST(ProjectorConfig, BadHomographies) {
  const auto withHomography = [](json h) {
    return projectorSectionError([&](json& s) { s["projectors"][0]["homography"] = h; });
  };
  const std::string field = "projectorArray.projectors[0].homography";
  EXPECT_EQ(withHomography(json::parse("[[1,0,0],[2,0,0],[0,0,1]]")).field(), field);      // singular
  EXPECT_EQ(withHomography(json::parse("[[1,0,0],[0,1,0],[0.01,0,-1]]")).field(), field);  // w <= 0 at a corner
  EXPECT_EQ(withHomography(json::parse("[[1,0,0],[0,1,0]]")).field(), field);              // 2 rows
  EXPECT_EQ(withHomography(json::parse("[[1,0,0],[0,1,\"x\"],[0,0,1]]")).field(), field);  // not a number
}

TEST(ProjectorConfig, StructuralErrors) {
  EXPECT_EQ(projectorSectionError([](json& s) { s["observerDistanse"] = 1; }).field(),
            "projectorArray.observerDistanse");
  EXPECT_EQ(projectorSectionError([](json& s) {
              s["projectors"][0]["pos"] = {0, 0, -1};
            }).field(),
            "projectorArray.projectors[0].pos");
  EXPECT_EQ(projectorSectionError([](json& s) { s.erase("image"); }).field(), "projectorArray.projectors[0].width");
  json tooMany = validConfig();
  for (int k = 0; k < 128; ++k) tooMany["projectorArray"]["projectors"].push_back({{"position", {k, 0, -100}}});
  EXPECT_EQ(errorOf(tooMany).field(), "projectorArray.projectors");
  json noSection = validConfig();
  noSection.erase("projectorArray");
  EXPECT_EQ(errorOf(noSection).field(), "projectorArray");
  json wrongModel = validConfig();
  wrongModel["model"] = "pinhole";
  EXPECT_EQ(errorOf(wrongModel).field(), "projectorArray");
  json badModel = validConfig();
  badModel["model"] = "projector";
  EXPECT_THAT(errorOf(badModel).expected(), HasSubstr("projector-array"));
}

TEST(ProjectorConfig, ParamsNeedProjectorModel) {
  EXPECT_THROW(makeProjectorArrayParams(builtinDisplay("portrait"), test::testBounds()), ConfigError);
}

}  // namespace
}  // namespace ht
