// footprint_sampling_test.cpp - where the samples of a footprint go (camera_models/footprint_sampling.h): one sample is
// the centre; two samples take one half of the footprint each on both axes (for a lenticular subpixel, one half of
// its view-phase width each), for every target and seed; four R2 samples take one quarter each in x.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "camera_models/footprint_sampling.h"

namespace ht {
namespace {

using gpu_shared::footprint_sample;
using gpu_shared::HT_FILTER_BOX;

TEST(FootprintSampling, OneSampleIsTheCentre) {
  for (std::uint32_t target = 0; target < 100; ++target)
    EXPECT_EQ(footprint_sample(target, 0, 1, 7, HT_FILTER_BOX), glm::vec2(0.5f));
}

TEST(FootprintSampling, TwoSamplesTakeOneHalfEachOnBothAxes) {
  for (std::uint32_t seed : {0u, 7u, 12345u}) {
    for (std::uint32_t target = 0; target < 10000; ++target) {
      const glm::vec2 a = footprint_sample(target, 0, 2, seed, HT_FILTER_BOX);
      const glm::vec2 b = footprint_sample(target, 1, 2, seed, HT_FILTER_BOX);
      ASSERT_NE(a.x < 0.5f, b.x < 0.5f) << "target " << target << " seed " << seed;
      ASSERT_NE(a.y < 0.5f, b.y < 0.5f) << "target " << target << " seed " << seed;
      ASSERT_NEAR(std::fabs(a.x - b.x), 0.5f, 1e-6f);
    }
  }
}

TEST(FootprintSampling, FourSamplesTakeOneQuarterEachInX) {
  for (std::uint32_t target = 0; target < 10000; ++target) {
    int quarters[4] = {0, 0, 0, 0};
    for (std::uint32_t s = 0; s < 4; ++s) {
      const glm::vec2 u = footprint_sample(target, s, 4, 3, HT_FILTER_BOX);
      ASSERT_TRUE(u.x >= 0.0f && u.x < 1.0f && u.y >= 0.0f && u.y < 1.0f);
      ++quarters[std::min(3, static_cast<int>(u.x * 4.0f))];
    }
    // R2's x generator 1/g = 0.7549 puts 4 consecutive points 0.245-0.265 apart (mod 1): at most 2 per quarter.
    for (int q : quarters) ASSERT_LE(q, 2) << "target " << target;
  }
}

}  // namespace
}  // namespace ht
