// pixel_encoding_test.cpp - the sRGB transfer functions (common/srgb.h) against their definition (IEC 61966-2-1),
// the 8-bit quantisation, the decode/encode round trip of every code, and the raw RGBA8 / RGBA16F buffers.
#include "frame_io/pixel_encoding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "common/srgb.h"

namespace ht::frame_io {
namespace {

using gpu_shared::ht_srgb_decode;
using gpu_shared::ht_srgb_encode;

double referenceOetf(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }
double referenceEotf(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

TEST(Srgb, EncodeMatchesTheFormulaOnBothSegments) {
  for (int i = 0; i <= 1000; ++i) {
    const double c = i / 1000.0;
    EXPECT_NEAR(ht_srgb_encode(float(c)), referenceOetf(c), 2e-6) << "c = " << c;
  }
  EXPECT_NEAR(ht_srgb_encode(0.002f), 12.92 * 0.002, 1e-7);  // linear toe
  EXPECT_NEAR(ht_srgb_encode(0.18f), 0.4613561, 1e-6);       // mid grey
  EXPECT_LE(ht_srgb_encode(1.0f), 1.0f);
}

TEST(Srgb, DecodeMatchesTheFormulaAndInvertsEncode) {
  for (int i = 0; i <= 1000; ++i) {
    const double v = i / 1000.0;
    EXPECT_NEAR(ht_srgb_decode(float(v)), referenceEotf(v), 2e-6) << "v = " << v;
    EXPECT_NEAR(ht_srgb_encode(ht_srgb_decode(float(v))), v, 2e-6) << "v = " << v;
  }
}

TEST(Srgb, EightBitCodesAreRoundedFromTheFormula) {
  for (int i = 0; i <= 4096; ++i) {
    const double c = i / 4096.0;
    EXPECT_EQ(srgbEncode8(float(c)), std::lround(255.0 * referenceOetf(c))) << "c = " << c;
  }
  EXPECT_EQ(srgbEncode8(0.5f), 188);
  EXPECT_EQ(srgbEncode8(0.0f), 0);
  EXPECT_EQ(srgbEncode8(1.0f), 255);
}

TEST(Srgb, EveryEightBitCodeSurvivesDecodeThenEncode) {
  for (int code = 0; code < 256; ++code) {
    EXPECT_EQ(srgbEncode8(srgbDecode8(std::uint8_t(code))), code);
    EXPECT_NEAR(srgbDecode8(std::uint8_t(code)), referenceEotf(code / 255.0), 1e-6);
  }
}

TEST(Srgb, ClampsOutOfRangeAndNan) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(srgbEncode8(-1.0f), 0);
  EXPECT_EQ(srgbEncode8(7.5f), 255);
  EXPECT_EQ(srgbEncode8(inf), 255);
  EXPECT_EQ(srgbEncode8(-inf), 0);
  EXPECT_EQ(srgbEncode8(nan), 0);
  EXPECT_EQ(ht_srgb_decode(nan), 0.0f);
  EXPECT_EQ(ht_srgb_decode(2.0f), 1.0f);
  EXPECT_EQ(linearEncode8(0.5f), 128);
  EXPECT_EQ(linearEncode8(2.0f), 255);
  EXPECT_EQ(linearEncode8(nan), 0);
}

TEST(RawPixels, Rgba8EncodesColourAsSrgbAndAlphaLinearly) {
  const std::vector<float> rgba = {0.5f, 0.0f, 1.0f, 0.5f, 0.18f, 2.0f, -1.0f, 1.0f};
  const std::vector<std::uint8_t> bytes = encodeRgba8Srgb(rgba);
  EXPECT_EQ(bytes, (std::vector<std::uint8_t>{188, 0, 255, 128, 118, 255, 0, 255}));
}

TEST(RawPixels, Rgba16fIsLittleEndianHalfOfTheLinearValue) {
  const std::vector<float> rgba = {1.0f, -2.0f, 0.5f, 65504.0f};
  const std::vector<std::uint8_t> bytes = encodeRgba16fLinear(rgba);
  ASSERT_EQ(bytes.size(), 8u);
  const std::uint16_t expected[4] = {0x3c00, 0xc000, 0x3800, 0x7bff};  // IEEE 754 binary16
  for (int i = 0; i < 4; ++i) EXPECT_EQ(bytes[2 * i] | bytes[2 * i + 1] << 8, expected[i]) << i;
}

}  // namespace
}  // namespace ht::frame_io
