// srgb_test.cpp - the sRGB OETF against its definition (IEC 61966-2-1) and the 8-bit quantisation.
#include "cli/srgb.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ht::cli {
namespace {

double referenceOetf(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

TEST(CliSrgb, MatchesTheFormulaOnBothSegments) {
  for (int i = 0; i <= 1000; ++i) {
    const double c = i / 1000.0;
    EXPECT_NEAR(srgbEncode(float(c)), referenceOetf(c), 2e-6) << "c = " << c;
  }
  EXPECT_NEAR(srgbEncode(0.002f), 12.92 * 0.002, 1e-7);  // linear toe
  EXPECT_NEAR(srgbEncode(0.18f), 0.4613561, 1e-6);      // mid grey
}

TEST(CliSrgb, EightBitCodesAreRoundedFromTheFormula) {
  for (int i = 0; i <= 4096; ++i) {
    const double c = i / 4096.0;
    EXPECT_EQ(srgbEncode8(float(c)), std::lround(255.0 * referenceOetf(c))) << "c = " << c;
  }
  EXPECT_EQ(srgbEncode8(0.5f), 188);
  EXPECT_EQ(srgbEncode8(0.0f), 0);
  EXPECT_EQ(srgbEncode8(1.0f), 255);
}

TEST(CliSrgb, ClampsOutOfRangeAndNan) {
  EXPECT_EQ(srgbEncode8(-1.0f), 0);
  EXPECT_EQ(srgbEncode8(7.5f), 255);
  EXPECT_EQ(srgbEncode8(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(srgbEncode8(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(linearEncode8(0.5f), 128);
  EXPECT_EQ(linearEncode8(2.0f), 255);
  EXPECT_EQ(linearEncode8(std::numeric_limits<float>::quiet_NaN()), 0);
}

}  // namespace
}  // namespace ht::cli
