// image_encoding_test.cpp - PNG / EXR / multiView EXR bytes read back through frame_io's reader: stored sample types,
// values (8-bit sRGB codes, half and float), orientation, unassociated alpha, attributes, determinism, and refusals.
#include "frame_io/image_encoding.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "coded_views.h"
#include "common/error.h"
#include "frame_io/image_reading.h"
#include "frame_io/pixel_encoding.h"

namespace ht::frame_io {
namespace {

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
      image.rgba.push_back(float(x) / float(image.width - 1));           // 0..1 left to right
      image.rgba.push_back(float(y) / float(image.height - 1) * 1.25f);  // 0..1.25 top to bottom
      image.rgba.push_back(0.001f * float(x + y) - 0.002f);              // toe, includes negatives
      image.rgba.push_back(0.25f + 0.1f * float(y));                     // alpha
    }
  }
  return image;
}

using test::codedViews;

TEST(ImageEncoding, PngIsEightBitSrgbTopRowFirstWithUnassociatedAlpha) {
  const TestImage image = makeTestImage();
  const ImageFile back = decodeImage(encodeImage(image.view(), ImageFormat::Png8Srgb), "frame.png");
  ASSERT_EQ(back.width, 7u);
  ASSERT_EQ(back.height, 5u);
  EXPECT_THAT(back.channelTypes,
              ElementsAre(SampleType::UInt8, SampleType::UInt8, SampleType::UInt8, SampleType::UInt8));
  ASSERT_EQ(back.rgba.size(), image.rgba.size());
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    const bool alpha = i % 4 == 3;
    const std::uint8_t stored = alpha ? linearEncode8(back.rgba[i]) : srgbEncode8(back.rgba[i]);
    const std::uint8_t expected = alpha ? linearEncode8(image.rgba[i]) : srgbEncode8(image.rgba[i]);
    EXPECT_EQ(stored, expected) << "value index " << i;  // colour not divided by alpha
  }
  // Row 0 of the input is the first scanline of the file: its green is 0, the last row's is clamped to 1.
  EXPECT_EQ(back.rgba[1], 0.0f);
  EXPECT_EQ(back.rgba[(4 * 7 + 6) * 4 + 1], 1.0f);
  EXPECT_EQ(back.attribute("Software"), "holotrace");
}

TEST(ImageEncoding, ExrHalfAndFloatRoundTripLinearValues) {
  const TestImage image = makeTestImage();
  const ImageFile half = decodeImage(encodeImage(image.view(), ImageFormat::ExrHalf), "half.exr");
  const ImageFile full = decodeImage(encodeImage(image.view(), ImageFormat::ExrFloat), "float.exr");
  EXPECT_EQ(half.channelTypes.front(), SampleType::Half);
  EXPECT_EQ(full.channelTypes.front(), SampleType::Float);
  ASSERT_EQ(half.rgba.size(), image.rgba.size());
  ASSERT_EQ(full.rgba.size(), image.rgba.size());
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    EXPECT_EQ(full.rgba[i], image.rgba[i]) << "float EXR, value index " << i;  // bit-exact, no clamping
    EXPECT_NEAR(half.rgba[i], image.rgba[i], std::abs(image.rgba[i]) * 1e-3 + 1e-6) << "half EXR, index " << i;
  }
  EXPECT_EQ(full.attribute("compression"), "zip");
}

TEST(ImageEncoding, SamePixelsGiveTheSameBytesWithoutADate) {
  const TestImage image = makeTestImage();
  for (ImageFormat format : {ImageFormat::Png8Srgb, ImageFormat::ExrHalf}) {
    const std::vector<std::uint8_t> first = encodeImage(image.view(), format, {{"ImageDescription", "x"}});
    EXPECT_EQ(encodeImage(image.view(), format, {{"ImageDescription", "x"}}), first);
    const ImageFile back = decodeImage(first, format == ImageFormat::Png8Srgb ? "a.png" : "a.exr");
    EXPECT_EQ(back.attribute("ImageDescription"), "x");
    EXPECT_EQ(back.attribute("DateTime"), "");
  }
}

TEST(ImageEncoding, MultiViewExrHoldsEveryViewUnderItsName) {
  const std::vector<float> rgba = codedViews(3, 5, 2);
  const std::vector<std::uint8_t> bytes =
      encodeMultiViewExr({5, 2, 3, rgba}, {"view00", "view01", "view02"}, ImageFormat::ExrFloat);
  const ImageFile back = decodeImage(bytes, "views.exr");
  EXPECT_THAT(back.viewNames, ElementsAre("view00", "view01", "view02"));
  ASSERT_EQ(back.channelNames.size(), 12u);
  EXPECT_THAT(back.channelNames, ::testing::Contains("view01.R"));
  ASSERT_EQ(back.views, 3u);
  EXPECT_EQ(back.rgba, rgba);  // every view, every value, in the order written
}

TEST(ImageEncoding, NamedChannelsExrKeepsNamesAndStorage) {
  const std::vector<float> values = {1, 2, 3, 4, 5, 6};  // 3x1 pixels of 2 channels
  const ImageHeader header = decodeImage(encodeExrChannels(3, 1, {"u", "v"}, values, ImageFormat::ExrHalf), "c.exr");
  EXPECT_THAT(header.channelNames, ElementsAre("u", "v"));
  EXPECT_THAT(header.channelTypes, ElementsAre(SampleType::Half, SampleType::Half));
}

TEST(ImageEncoding, MismatchedBuffersAreRefused) {
  TestImage image = makeTestImage();
  image.rgba.pop_back();
  EXPECT_THROW(encodeImage(image.view(), ImageFormat::Png8Srgb), IoError);
  EXPECT_THROW(encodeImage({0, 0, {}}, ImageFormat::ExrFloat), IoError);
  const std::vector<float> rgba = codedViews(2, 4, 4);
  EXPECT_THROW(encodeMultiViewExr({4, 4, 2, rgba}, {"a", "b", "c"}, ImageFormat::ExrHalf), IoError);
  EXPECT_THROW(encodeMultiViewExr({4, 4, 2, rgba}, {"a", "b"}, ImageFormat::Png8Srgb), IoError);
  EXPECT_THROW(encodeExrChannels(3, 1, {"u", "v"}, std::vector<float>(5), ImageFormat::ExrFloat), IoError);
}

}  // namespace
}  // namespace ht::frame_io
