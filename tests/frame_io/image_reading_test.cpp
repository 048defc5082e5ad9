// image_reading_test.cpp - reading PNG / EXR into linear RGBA: files and bytes, channel mapping (RGB without alpha,
// grey), views of a multiView EXR, and bad input refused with the file named, before any pixel memory is allocated.
#include "frame_io/image_reading.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>

#include "common/error.h"
#include "frame_io/atomic_output_file.h"
#include "tests/common/temp_directory.h"

namespace ht::frame_io {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string readError(const std::function<void()>& read) {
  try {
    read();
  } catch (const IoError& e) { return e.what(); }
  ADD_FAILURE() << "read accepted the input";
  return "";
}

TEST(ImageReading, PngFileReadsAsLinearRgba) {
  test::TempDirectory dir;
  const std::vector<float> rgba = {0.0f, 0.5f, 1.0f, 1.0f, 0.214041f, 0.0f, 0.0f, 0.5f};  // 2x1
  const OutputFile file{dir.path() / "two.png", encodeImage({2, 1, rgba}, ImageFormat::Png8Srgb)};
  writeFilesAtomically({&file, 1});
  const ImageFile back = readImageFile(dir.path() / "two.png");
  ASSERT_EQ(back.width, 2u);
  ASSERT_EQ(back.height, 1u);
  EXPECT_EQ(back.views, 1u);
  EXPECT_TRUE(back.viewNames.empty());
  for (std::size_t i = 0; i < rgba.size(); ++i) EXPECT_NEAR(back.rgba[i], rgba[i], 4e-3) << i;  // 8-bit steps
  EXPECT_EQ(back.rgba[0], 0.0f);
  EXPECT_EQ(back.rgba[2], 1.0f);
}

TEST(ImageReading, RgbWithoutAlphaReadsOpaqueAndGreyFillsRgb) {
  const ImageFile rgb = decodeImage(
      encodeExrChannels(1, 1, {"B", "G", "R"}, std::vector<float>{3, 2, 1}, ImageFormat::ExrFloat), "rgb.exr");
  EXPECT_EQ(rgb.rgba, (std::vector<float>{1, 2, 3, 1}));
  const ImageFile grey =
      decodeImage(encodeExrChannels(2, 1, {"Y"}, std::vector<float>{0.25f, 4.0f}, ImageFormat::ExrFloat), "y.exr");
  EXPECT_EQ(grey.rgba, (std::vector<float>{0.25f, 0.25f, 0.25f, 1, 4, 4, 4, 1}));
}

TEST(ImageReading, ChannelsArePickedByNameOrPosition) {
  // Two unnamed-looking channels: grey + alpha by position.
  const ImageFile greyAlpha = decodeImage(
      encodeExrChannels(1, 1, {"u", "v"}, std::vector<float>{0.5f, 0.25f}, ImageFormat::ExrFloat), "ga.exr");
  EXPECT_EQ(greyAlpha.rgba, (std::vector<float>{0.5f, 0.5f, 0.5f, 0.25f}));
  // Five channels and no R, G, B or Y: no way to tell colour, refused naming the file.
  const std::vector<std::uint8_t> five =
      encodeExrChannels(1, 1, {"a", "b", "c", "d", "e"}, std::vector<float>(5), ImageFormat::ExrFloat);
  EXPECT_THAT(readError([&] { decodeImage(five, "five.exr"); }), HasSubstr("five.exr"));
}

TEST(ImageReading, MissingOrGarbageFilesAreIoErrorsNamingThem) {
  test::TempDirectory dir;
  EXPECT_THAT(readError([&] { readImageFile(dir.path() / "none.png"); }), HasSubstr("none.png"));
  std::ofstream(dir.path() / "junk.png") << "not an image at all";
  EXPECT_THAT(readError([&] { readImageFile(dir.path() / "junk.png"); }), HasSubstr("junk.png"));
  const std::vector<std::uint8_t> junk(100, 0x42);
  EXPECT_THAT(readError([&] { decodeImage(junk, "junk.exr"); }), HasSubstr("junk.exr"));
}

// A valid 4x4 EXR whose header is edited to claim 30000 x 30000 pixels: refused from the header, no 3.6 G floats.
TEST(ImageReading, HugeClaimedSizeIsRefusedBeforeAllocating) {
  std::vector<std::uint8_t> bytes = encodeImage({4, 4, std::vector<float>(64, 0.5f)}, ImageFormat::ExrFloat);
  const std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0';
  const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
  ASSERT_NE(at, bytes.end());
  const std::int32_t window[4] = {0, 0, 29999, 29999};
  std::memcpy(&*(at + std::ptrdiff_t(key.size()) + 4), window, sizeof window);  // after the 4-byte attribute size
  const std::string error = readError([&] { decodeImage(bytes, "huge.exr"); });
  EXPECT_THAT(error, HasSubstr("huge.exr"));
  const std::vector<std::uint8_t> wide =
      encodeExrChannels(40000, 1, {"Y"}, std::vector<float>(40000), ImageFormat::ExrHalf);
  EXPECT_THAT(readError([&] { decodeImage(wide, "wide.exr"); }), HasSubstr("32768"));
}

}  // namespace
}  // namespace ht::frame_io
