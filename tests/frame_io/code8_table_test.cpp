// code8_table_test.cpp - the looked-up 8-bit codes (frame_io/code8_table.h) against the functions they stand for
// (srgbEncode8, linearEncode8): at and around every code step and every bucket edge, on random bit patterns of every
// kind (NaN, infinities, negatives, denormals, above 1), and through encodeRgba8Srgb on frames large enough to be cut
// across threads.
#include "frame_io/code8_table.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "frame_io/pixel_encoding.h"

namespace ht::frame_io {
namespace {

struct NamedCode {
  const char* name;
  Code8Table::Reference reference;
};
const NamedCode kCodes[] = {{"srgbEncode8", srgbEncode8}, {"linearEncode8", linearEncode8}};

// The bits of the least float in [0, 1] whose code is >= k, found by walking the reference (test-side bisection).
std::uint32_t stepBits(Code8Table::Reference reference, unsigned k) {
  std::uint32_t lo = 0, hi = std::bit_cast<std::uint32_t>(1.0f);
  while (lo < hi) {
    const std::uint32_t mid = lo + (hi - lo) / 2;
    if (reference(std::bit_cast<float>(mid)) >= k) {
      hi = mid;
    } else {
      lo = mid + 1;
    }
  }
  return lo;
}

TEST(Code8Table, EqualsItsReferenceAroundEveryCodeStep) {
  for (const NamedCode& c : kCodes) {
    const Code8Table table(c.reference);
    std::uint64_t checked = 0;
    for (unsigned k = 1; k <= 255; ++k) {
      const std::uint32_t step = stepBits(c.reference, k);
      for (std::int64_t d = -300; d <= 300; ++d) {
        const std::int64_t bits = std::int64_t{step} + d;
        if (bits < 0 || bits > std::bit_cast<std::uint32_t>(1.0f)) continue;
        const float x = std::bit_cast<float>(static_cast<std::uint32_t>(bits));
        ASSERT_EQ(table(x), c.reference(x)) << c.name << " x = " << x << " (bits " << bits << ", step " << k << ")";
        ++checked;
      }
    }
    EXPECT_GT(checked, 100'000u) << c.name;
  }
}

TEST(Code8Table, EqualsItsReferenceAtEveryBucketEdge) {
  for (const NamedCode& c : kCodes) {
    const Code8Table table(c.reference);
    for (std::uint32_t bucket = 0; bucket <= (std::bit_cast<std::uint32_t>(1.0f) >> 16); ++bucket) {
      for (std::int64_t d = -2; d <= 2; ++d) {
        const std::int64_t bits = (std::int64_t{bucket} << 16) + d;
        if (bits < 0) continue;
        const float x = std::bit_cast<float>(static_cast<std::uint32_t>(bits));
        ASSERT_EQ(table(x), c.reference(x)) << c.name << " bits " << bits;
      }
    }
  }
}

TEST(Code8Table, EqualsItsReferenceOnRandomBitsOfEveryKind) {
  std::mt19937 rng(20261204);
  std::uniform_int_distribution<std::uint32_t> anyBits;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (const NamedCode& c : kCodes) {
    const Code8Table table(c.reference);
    for (int i = 0; i < 1'000'000; ++i) {
      const float x = i % 2 ? std::bit_cast<float>(anyBits(rng)) : unit(rng);  // half in [0, 1)
      ASSERT_EQ(table(x), c.reference(x)) << c.name << " bits " << std::bit_cast<std::uint32_t>(x);
    }
    const float inf = std::numeric_limits<float>::infinity();
    for (float x : {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, inf, -inf, std::numeric_limits<float>::quiet_NaN(),
                    -std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::denorm_min(),
                    std::numeric_limits<float>::min(), std::nextafter(1.0f, 0.0f), std::nextafter(1.0f, 2.0f),
                    std::numeric_limits<float>::max()}) {
      EXPECT_EQ(table(x), c.reference(x)) << c.name << " x = " << x;
    }
  }
}

// A code that takes all 255 steps at once has more steps in one bucket than a lookup takes: refused.
TEST(Code8Table, RefusesACodeWithMoreStepsInABucketThanALookupTakes) {
  const Code8Table::Reference cliff = [](float x) -> std::uint8_t {
    return x >= 0.3f ? 255 : 0;
  };  // 0.3f: inside a bucket
  EXPECT_THROW(Code8Table{cliff}, std::invalid_argument);
}

TEST(RawPixels, Rgba8OfALargeFrameEqualsTheCodeOfEveryValue) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> values(-0.1f, 1.3f);
  std::vector<float> rgba(4 * 1'300'001);  // several threads' worth, not a multiple of their count
  for (float& v : rgba) v = values(rng);
  rgba[17] = std::numeric_limits<float>::quiet_NaN();
  rgba[4 * 1'300'000 + 3] = std::numeric_limits<float>::infinity();
  const std::vector<std::uint8_t> bytes = encodeRgba8Srgb(rgba);
  ASSERT_EQ(bytes.size(), rgba.size());
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    const std::uint8_t expected = i % 4 == 3 ? linearEncode8(rgba[i]) : srgbEncode8(rgba[i]);
    ASSERT_EQ(bytes[i], expected) << "value " << i << " = " << rgba[i];
  }
  std::vector<std::uint8_t> wrongSize(rgba.size() - 4);
  EXPECT_THROW(encodeRgba8Srgb(rgba, wrongSize), std::invalid_argument);
}

}  // namespace
}  // namespace ht::frame_io
