// image_file_writer_test.cpp - PNG/EXR round trips through OpenImageIO, orientation, and failures that
// must leave no file behind.
#include "cli/image_file_writer.h"

#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

#include "cli/srgb.h"
#include "common/error.h"
#include "temp_directory.h"

namespace ht::cli {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

struct TestImage {
  std::uint32_t width = 7, height = 5;
  std::vector<float> rgba;
  RgbaImageView view() const { return {width, height, rgba}; }
};

// Distinct values per pixel, including out-of-range ones, so orientation and clamping are both visible.
TestImage makeTestImage() {
  TestImage image;
  for (std::uint32_t y = 0; y < image.height; ++y) {
    for (std::uint32_t x = 0; x < image.width; ++x) {
      image.rgba.push_back(float(x) / float(image.width - 1));          // 0..1 left to right
      image.rgba.push_back(float(y) / float(image.height - 1) * 1.25f);  // 0..1.25 top to bottom
      image.rgba.push_back(0.001f * float(x + y) - 0.002f);             // toe, includes negatives
      image.rgba.push_back(0.25f + 0.1f * float(y));                    // alpha
    }
  }
  return image;
}

struct ReadBack {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  // as float, in the file's value range (0..1 for 8-bit)
  std::vector<std::uint8_t> bytes;  // only for 8-bit files
};

ReadBack readBack(const fs::path& path, bool asBytes) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // the raw stored values, no premultiplication on read
  auto in = OIIO::ImageInput::open(path.string(), &config);
  EXPECT_TRUE(in) << OIIO::geterror();
  ReadBack result;
  if (!in) return result;
  result.spec = in->spec();
  const std::size_t count = std::size_t(result.spec.width) * result.spec.height * result.spec.nchannels;
  if (asBytes) {
    result.bytes.resize(count);
    EXPECT_TRUE(in->read_image(0, 0, 0, result.spec.nchannels, OIIO::TypeDesc::UINT8, result.bytes.data()));
  } else {
    result.pixels.resize(count);
    EXPECT_TRUE(in->read_image(0, 0, 0, result.spec.nchannels, OIIO::TypeDesc::FLOAT, result.pixels.data()));
  }
  in->close();
  return result;
}

TEST(CliImageFileWriter, PngIsEightBitSrgbTopRowFirst) {
  test::TempDirectory dir;
  const TestImage image = makeTestImage();
  const fs::path path = dir.path() / "frame.png";
  writeImageFile(path, image.view(), ImageFormat::Png8Srgb);

  const ReadBack back = readBack(path, true);
  ASSERT_EQ(back.spec.width, 7);
  ASSERT_EQ(back.spec.height, 5);
  ASSERT_EQ(back.spec.nchannels, 4);
  EXPECT_EQ(back.spec.format, OIIO::TypeDesc::UINT8);
  ASSERT_EQ(back.bytes.size(), image.rgba.size());
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    const double v = std::clamp(double(image.rgba[i]), 0.0, 1.0);
    const double encoded = i % 4 == 3 ? v : (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055);
    EXPECT_EQ(back.bytes[i], std::lround(255.0 * encoded)) << "value index " << i;
  }
  // Row 0 of the input is the first scanline of the file: its green is 0, the last row's is clamped to 255.
  EXPECT_EQ(back.bytes[1], 0);
  EXPECT_EQ(back.bytes[(4 * 7 + 6) * 4 + 1], 255);
  EXPECT_THAT(dir.entries(), ElementsAre("frame.png"));
}

TEST(CliImageFileWriter, ExrHalfAndFloatRoundTripLinearValues) {
  test::TempDirectory dir;
  const TestImage image = makeTestImage();
  writeImageFile(dir.path() / "half.exr", image.view(), ImageFormat::ExrHalf);
  writeImageFile(dir.path() / "float.exr", image.view(), ImageFormat::ExrFloat);

  const ReadBack half = readBack(dir.path() / "half.exr", false);
  const ReadBack full = readBack(dir.path() / "float.exr", false);
  EXPECT_EQ(half.spec.format, OIIO::TypeDesc::HALF);
  EXPECT_EQ(full.spec.format, OIIO::TypeDesc::FLOAT);
  ASSERT_EQ(half.pixels.size(), image.rgba.size());
  ASSERT_EQ(full.pixels.size(), image.rgba.size());
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    EXPECT_EQ(full.pixels[i], image.rgba[i]) << "float EXR, value index " << i;  // bit-exact, no clamping
    EXPECT_NEAR(half.pixels[i], image.rgba[i], std::abs(image.rgba[i]) * 1e-3 + 1e-6) << "half EXR, index " << i;
  }
  EXPECT_THAT(dir.entries(), ElementsAre("float.exr", "half.exr"));
}

TEST(CliImageFileWriter, CreatesMissingDirectoriesAndReplacesExistingFiles) {
  test::TempDirectory dir;
  const TestImage image = makeTestImage();
  const fs::path path = dir.path() / "a" / "b" / "frame.png";
  writeImageFile(path, image.view(), ImageFormat::Png8Srgb);
  ASSERT_TRUE(fs::is_regular_file(path));
  std::ofstream(path) << "stale";
  writeImageFile(path, image.view(), ImageFormat::Png8Srgb);
  EXPECT_EQ(readBack(path, true).spec.width, 7);
  EXPECT_EQ(fs::status(path).permissions() & fs::perms::others_read, fs::perms::others_read);
}

TEST(CliImageFileWriter, ParentThatCannotBeCreatedThrowsAndLeavesNoFile) {
  test::TempDirectory dir;
  std::ofstream(dir.path() / "blocker") << "a regular file where a directory is needed";
  const fs::path path = dir.path() / "blocker" / "sub" / "frame.png";
  try {
    writeImageFile(path, makeTestImage().view(), ImageFormat::Png8Srgb);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
    EXPECT_THAT(e.what(), HasSubstr("cannot create directory"));
  }
  EXPECT_THAT(dir.entries(), ElementsAre("blocker"));
}

TEST(CliImageFileWriter, FailureAfterWritingRemovesTheTemporaryFile) {
  test::TempDirectory dir;
  const fs::path path = dir.path() / "frame.exr";
  fs::create_directories(path / "occupied");  // a non-empty directory: the final rename must fail
  try {
    writeImageFile(path, makeTestImage().view(), ImageFormat::ExrHalf);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
  }
  EXPECT_THAT(dir.entries(), ElementsAre("frame.exr"));
  EXPECT_TRUE(fs::is_directory(path));
}

TEST(CliImageFileWriter, MismatchedPixelCountThrowsBeforeCreatingAnything) {
  test::TempDirectory dir;
  TestImage image = makeTestImage();
  image.rgba.pop_back();
  EXPECT_THROW(writeImageFile(dir.path() / "out" / "frame.png", image.view(), ImageFormat::Png8Srgb), IoError);
  const RgbaImageView empty{0, 0, {}};
  EXPECT_THROW(writeImageFile(dir.path() / "frame.png", empty, ImageFormat::ExrFloat), IoError);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace ht::cli
