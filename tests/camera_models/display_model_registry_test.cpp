// display_model_registry_test.cpp - walks every row of the display-model registry through every CPU stage: its
// example config parses to the row's model (and its section belongs to it alone), setup makes a camera of the row's
// model, the shape and the GPU block are filled, the view layout matches the shape. A model missing from a stage
// fails here; tests/gpu/display_model_render_test.cpp renders every row.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <set>
#include <string>

#include "camera_models/display_model_registry.h"
#include "camera_models/ray_table.h"
#include "camera_test_support.h"

namespace ht::test {
namespace {

using ::testing::HasSubstr;

// A 6 x 4 table of parallel rays on a plane (only the ray-table row reads it).
std::shared_ptr<const RayTable> registryTestTable() {
  auto table = std::make_shared<RayTable>();
  table->width = 6;
  table->height = 4;
  for (std::uint32_t i = 0; i < table->width * table->height; ++i) {
    table->origins.push_back(glm::vec3(float(i % table->width), float(i / table->width), 0.0f));
    table->directions.push_back(glm::vec3(0.0f, 0.0f, -1.0f));
  }
  return table;
}

DisplayConfig exampleOf(const DisplayModelRow& row) {
  return parseDisplayConfig(row.example, "example:" + std::string(row.name), HT_TEST_DATA_DIR);
}

bool allZero(const gpu_shared::CameraBlock& block) {
  static const gpu_shared::CameraBlock zero{};
  return std::memcmp(&block, &zero, sizeof block) == 0;
}

TEST(DisplayModelRegistry, OneRowPerModelIdWithAUniqueName) {
  ASSERT_EQ(displayModels().size(), gpu_shared::HT_MODEL_COUNT);
  std::set<std::string_view> names, sections;
  for (std::size_t i = 0; i < displayModels().size(); ++i) {
    const DisplayModelRow& row = displayModels()[i];
    EXPECT_EQ(static_cast<std::size_t>(row.model), i) << row.name;
    EXPECT_EQ(&displayModelRow(row.model), &row) << row.name;
    EXPECT_EQ(displayModelName(row.model), row.name);
    EXPECT_TRUE(names.insert(row.name).second) << "duplicate name " << row.name;
    EXPECT_EQ(findConfigModel(row.name), row.inConfigs ? &row : nullptr) << row.name;
    if (!row.sectionKey.empty()) {
      EXPECT_TRUE(sections.insert(row.sectionKey).second) << "duplicate section " << row.sectionKey;
      EXPECT_NE(row.parseSection, nullptr) << row.name;
      EXPECT_NE(row.hasSection, nullptr) << row.name;
    }
    EXPECT_FALSE(row.example.empty()) << row.name;
  }
  EXPECT_EQ(findConfigModel("quilt"), nullptr);  // quilt cameras are a path of lenticular displays, not a config model
}

TEST(DisplayModelRegistry, EveryExampleParsesToItsModelWithItsOwnSectionOnly) {
  for (const DisplayModelRow& row : displayModels()) {
    const DisplayConfig config = exampleOf(row);
    EXPECT_EQ(config.model, row.inConfigs ? row.model : DisplayModel::Lenticular) << row.name;
    for (const DisplayModelRow& other : displayModels()) {
      if (other.hasSection == nullptr) continue;
      EXPECT_EQ(other.hasSection(config), other.model == config.model) << row.name << " / " << other.sectionKey;
    }
  }
}

TEST(DisplayModelRegistry, AModelSectionUnderAnotherModelNamesTheSection) {
  for (const DisplayModelRow& row : displayModels()) {
    if (row.sectionKey.empty()) continue;
    nlohmann::json example = nlohmann::json::parse(row.example);
    example["model"] = "pinhole";
    ConfigError e = catchConfigError([&] { parseDisplayConfig(example.dump(), "moved.json", HT_TEST_DATA_DIR); });
    EXPECT_EQ(e.field(), row.sectionKey);
    EXPECT_THAT(e.expected(), HasSubstr("unless model is \"" + std::string(row.name) + "\""));
  }
}

TEST(DisplayModelRegistry, UnknownModelErrorListsEveryConfigModel) {
  ConfigError e = catchConfigError([] { parseDisplayConfig(R"({"model":"holovizio"})", "display.json", ""); });
  for (const DisplayModelRow& row : displayModels()) {
    if (row.inConfigs) { EXPECT_THAT(e.expected(), HasSubstr("\"" + std::string(row.name) + "\"")) << row.name; }
  }
  EXPECT_THAT(e.expected(), ::testing::Not(HasSubstr("quilt")));
}

TEST(DisplayModelRegistry, EverySetupMakesACameraOfItsModelWithShapeBlockAndLayout) {
  for (const DisplayModelRow& row : displayModels()) {
    SCOPED_TRACE(std::string(row.name));
    const DisplayConfig config = exampleOf(row);
    const FrameCamera camera = row.makeCamera(config, testBounds(), registryTestTable());
    EXPECT_EQ(cameraModel(camera), row.model);

    const FrameShape shape = frameShape(camera);
    EXPECT_EQ(shape.model, static_cast<std::uint32_t>(row.model));
    EXPECT_GT(shape.width, 0u);
    EXPECT_GT(shape.height, 0u);
    EXPECT_GT(shape.views, 0u);
    EXPECT_LE(std::max(shape.width, shape.height), kMaxImageSide);
    EXPECT_EQ(shape.targetsPerPixel, gpu_shared::ht_model_has_subpixel_targets(shape.model) ? 3u : 1u);

    const gpu_shared::CameraBlock block = cameraBlock(camera);
    EXPECT_FALSE(allZero(block)) << "the GPU block of " << row.name << " stays empty";
    gpu_shared::CameraBlock direct{};
    row.writeBlock(camera, direct);
    EXPECT_EQ(std::memcmp(&block, &direct, sizeof block), 0);

    if (const std::optional<QuiltLayout> quilt = row.viewQuilt(config, camera, shape)) {
      EXPECT_EQ(quilt->views(), shape.views);
      EXPECT_EQ(quilt->tileWidth, shape.width);
      EXPECT_EQ(quilt->tileHeight, shape.height);
    }
  }
}

TEST(DisplayModelRegistry, SetupOfAnotherModelsConfigIsAConfigError) {
  const DisplayConfig pinhole = exampleOf(displayModelRow(DisplayModel::Pinhole));
  for (const DisplayModelRow& row : displayModels()) {
    if (row.model == DisplayModel::Pinhole) continue;
    EXPECT_THROW(row.makeCamera(pinhole, testBounds(), registryTestTable()), ConfigError) << row.name;
  }
}

}  // namespace
}  // namespace ht::test
