// ray_table_exr_test.cpp - ray-table EXR files: bit-exact round trip (with and without the phase channel), row
// orientation in the file, and the errors: missing / non-float32 channels, NaN values, oversized tables, missing files.
#include "frame_io/ray_table_exr.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "common/error.h"
#include "frame_io/atomic_output_file.h"
#include "frame_io/image_encoding.h"
#include "frame_io/image_reading.h"
#include "tests/common/temp_directory.h"

namespace ht::frame_io {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// Irregular values (not representable in half, negative zero included) so any conversion or reordering shows.
RayTable makeTable(std::uint32_t width, std::uint32_t height) {
  RayTable t;
  t.width = width;
  t.height = height;
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      t.origins.emplace_back(0.1234567f * float(x) - 3.3f, 1e-7f * float(y) + 2.5f, x == 0 ? -0.0f : 1.0f / 3.0f);
      t.directions.emplace_back(0.01f * float(x) + 0.001f * float(y), -0.02f * float(y), -1.0f);
    }
  }
  t.normalizeDirections();
  return t;
}

bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof(glm::vec3)) == 0; }

// Writes an EXR with arbitrary channels (rows as given: row 0 = top).
void writeRawExr(const fs::path& path, std::uint32_t width, std::uint32_t height, const std::vector<std::string>& names,
                 const std::vector<float>& pixels, ImageFormat format = ImageFormat::ExrFloat) {
  const OutputFile file{path, encodeExrChannels(width, height, names, pixels, format)};
  writeFilesAtomically({&file, 1});
}

const std::vector<std::string> kNames = {"origin.X",    "origin.Y",    "origin.Z",
                                         "direction.X", "direction.Y", "direction.Z"};

// A valid 3x2 table's pixels in file order (row 0 = top = y 1): origin (x, y, 0), direction (0, 0, -1).
std::vector<float> rawPixels() {
  std::vector<float> p;
  for (int row = 0; row < 2; ++row) {
    for (int x = 0; x < 3; ++x) {
      for (float v : {float(x), float(1 - row), 0.0f, 0.0f, 0.0f, -1.0f}) p.push_back(v);
    }
  }
  return p;
}

ConfigError readError(const fs::path& path) {
  try {
    readRayTableExr(path);
  } catch (const ConfigError& e) { return e; }
  ADD_FAILURE() << "read accepted " << path;
  return ConfigError("", "", "", "");
}

TEST(RayTableExr, RoundTripIsBitExact) {
  test::TempDirectory dir;
  const RayTable table = makeTable(17, 11);
  writeRayTableExr(dir.path() / "t.exr", table);
  std::vector<float> phase = {1.0f};
  const RayTable back = readRayTableExr(dir.path() / "t.exr", &phase);
  EXPECT_TRUE(phase.empty());
  ASSERT_EQ(back.width, 17u);
  ASSERT_EQ(back.height, 11u);
  ASSERT_EQ(back.origins.size(), table.origins.size());
  for (std::size_t i = 0; i < table.origins.size(); ++i) {
    EXPECT_TRUE(sameBits(back.origins[i], table.origins[i])) << i;
    EXPECT_TRUE(sameBits(back.directions[i], table.directions[i])) << i;
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"t.exr"});  // no temporary left
}

TEST(RayTableExr, PhaseChannelAndRowOrder) {
  test::TempDirectory dir;
  const RayTable table = makeTable(5, 4);
  std::vector<float> phase(20);
  for (std::size_t i = 0; i < phase.size(); ++i) phase[i] = 0.05f * float(i) - 0.3f;
  writeRayTableExr(dir.path() / "p.exr", table, phase);
  std::vector<float> back;
  readRayTableExr(dir.path() / "p.exr", &back);
  ASSERT_EQ(back.size(), phase.size());
  for (std::size_t i = 0; i < phase.size(); ++i) EXPECT_EQ(std::memcmp(&back[i], &phase[i], 4), 0) << i;
  // Seven float32 channels in the file.
  const ImageHeader header = readImageHeader(dir.path() / "p.exr");
  EXPECT_EQ(header.channelNames.size(), 7u);
  EXPECT_THAT(header.channelNames, ::testing::Contains("phase"));
  EXPECT_EQ(std::count(header.channelTypes.begin(), header.channelTypes.end(), SampleType::Float), 7);
  EXPECT_THROW(writeRayTableExr(dir.path() / "bad-phase.exr", table, std::vector<float>(3)), IoError);
}

// In the file, scanline 0 is the top row: table row y = height - 1 (rawPixels' rows: origin.y = 1 - row).
TEST(RayTableExr, FirstScanlineIsTheTopRow) {
  test::TempDirectory dir;
  writeRawExr(dir.path() / "r.exr", 3, 2, kNames, rawPixels());
  const RayTable t = readRayTableExr(dir.path() / "r.exr");
  EXPECT_EQ(t.origins[t.index(2, 1)], glm::vec3(2.0f, 1.0f, 0.0f));  // scanline 0
  EXPECT_EQ(t.origins[t.index(2, 0)], glm::vec3(2.0f, 0.0f, 0.0f));  // scanline 1
}

TEST(RayTableExr, MissingChannelIsNamed) {
  test::TempDirectory dir;
  std::vector<std::string> names = kNames;
  names[5] = "direction.W";
  writeRawExr(dir.path() / "m.exr", 3, 2, names, rawPixels());
  const ConfigError e = readError(dir.path() / "m.exr");
  EXPECT_EQ(e.file(), (dir.path() / "m.exr").string());
  EXPECT_EQ(e.field(), "direction.Z");
  EXPECT_EQ(e.value(), "(missing)");
  EXPECT_THAT(e.expected(), HasSubstr("direction.W"));  // lists what the file has
  // Too few channels at all (an ordinary RGB image).
  writeRawExr(dir.path() / "rgb.exr", 2, 2, {"R", "G", "B"}, std::vector<float>(12, 0.5f));
  EXPECT_EQ(readError(dir.path() / "rgb.exr").field(), "channels");
}

TEST(RayTableExr, HalfChannelsRejected) {
  test::TempDirectory dir;
  writeRawExr(dir.path() / "h.exr", 3, 2, kNames, rawPixels(), ImageFormat::ExrHalf);
  const ConfigError e = readError(dir.path() / "h.exr");
  EXPECT_THAT(e.expected(), HasSubstr("float32"));
}

TEST(RayTableExr, NaNRejected) {
  test::TempDirectory dir;
  std::vector<float> pixels = rawPixels();
  ASSERT_EQ(pixels.size(), 36u);
  pixels[6 * 4 + 1] = std::numeric_limits<float>::quiet_NaN();  // row 1 (y = 0), x = 1, origin.Y
  writeRawExr(dir.path() / "n.exr", 3, 2, kNames, pixels);
  const ConfigError e = readError(dir.path() / "n.exr");
  EXPECT_EQ(e.field(), "origin[x=1, y=0]");
  EXPECT_THAT(e.value(), HasSubstr("nan"));
  // A zero direction.
  pixels = rawPixels();
  pixels[6 * 0 + 5] = 0.0f;  // row 0 (y = 1), x = 0
  writeRawExr(dir.path() / "z.exr", 3, 2, kNames, pixels);
  EXPECT_EQ(readError(dir.path() / "z.exr").field(), "direction[x=0, y=1]");
  // The writer refuses a NaN table and leaves nothing behind.
  RayTable table = makeTable(4, 4);
  table.directions[5].x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(writeRayTableExr(dir.path() / "w.exr", table), ConfigError);
  EXPECT_FALSE(fs::exists(dir.path() / "w.exr"));
}

TEST(RayTableExr, UnitDirectionsOnRead) {
  test::TempDirectory dir;
  writeRawExr(dir.path() / "u.exr", 3, 2, kNames, [] {
    std::vector<float> p = rawPixels();
    p[3] = 3.0f;  // direction (3, 0, -1) at x = 0, y = 1
    return p;
  }());
  const RayTable t = readRayTableExr(dir.path() / "u.exr");
  EXPECT_NEAR(glm::length(glm::dvec3(t.directions[t.index(0, 1)])), 1.0, 1e-7);
  EXPECT_NEAR(t.directions[t.index(0, 1)].x, 3.0 / std::sqrt(10.0), 1e-7);
  EXPECT_EQ(t.origins[t.index(2, 1)], glm::vec3(2.0f, 1.0f, 0.0f));
}

TEST(RayTableExr, OversizedAndMissingFiles) {
  test::TempDirectory dir;
  writeRawExr(dir.path() / "wide.exr", 16385, 1, kNames, std::vector<float>(16385 * 6, 1.0f));
  const ConfigError e = readError(dir.path() / "wide.exr");
  EXPECT_EQ(e.field(), "size");
  EXPECT_EQ(e.value(), "16385x1");
  try {
    readRayTableExr(dir.path() / "nope.exr");
    ADD_FAILURE() << "read a missing file";
  } catch (const IoError& error) { EXPECT_THAT(error.what(), HasSubstr("nope.exr")); }
}

TEST(RayTableExr, LoadedThroughTheDisplayConfig) {
  test::TempDirectory dir;
  const RayTable table = makeTable(6, 3);
  fs::create_directories(dir.path() / "tables");
  writeRayTableExr(dir.path() / "tables" / "panel.exr", table);
  {
    std::ofstream config(dir.path() / "display.json");
    config << R"({"name": "calibrated", "model": "ray-table", "rayTable": {"file": "tables/panel.exr", "units": 0.5}})";
  }
  const DisplayConfig config = loadDisplayConfig(dir.path() / "display.json");
  const RayTable back = loadDisplayRayTable(config);
  ASSERT_EQ(back.origins.size(), table.origins.size());
  for (std::size_t i = 0; i < table.origins.size(); ++i) EXPECT_TRUE(sameBits(back.origins[i], table.origins[i]));
  const DisplayConfig missing =
      parseDisplayConfig(R"({"model": "ray-table", "rayTable": {"file": "gone.exr"}})", "cfg.json", dir.path());
  try {
    loadDisplayRayTable(missing);
    ADD_FAILURE() << "loaded a missing table";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "cfg.json");
    EXPECT_EQ(e.field(), "rayTable.file");
    EXPECT_THAT(e.value(), HasSubstr("gone.exr"));
  }
  EXPECT_THROW(loadDisplayRayTable(builtinDisplay("capture-8x6")), ConfigError);
}

}  // namespace
}  // namespace ht::frame_io
