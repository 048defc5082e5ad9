// code8_table.h - a monotone map from float to an 8-bit code, looked up instead of computed, with the same result
// for every float. The sRGB encoding of a frame (frame_io/pixel_encoding.h) is a powf per colour value: 11 ns here,
// 140 ms for one 1536x2048 panel image on one core, paid by every RGBA8 frame a stream sends and every frame the
// display sink shows. A table of the code's 255 steps gives the same bytes in a fraction of that.
//
// The table holds, for k = 1..255, the smallest float in [0, 1] whose code is >= k (found by bisection over the float
// bits, which order like the floats for x >= 0), and, for each bucket of 2^16 consecutive float bit patterns, the
// code of its first value. code(x) for x in [0, 1] is the bucket's code plus the steps in the bucket below x: no more
// than two for the sRGB and linear codes, whose steps are wider than any bucket, so two branch-free compares. That
// equals the reference function wherever the reference is monotone in x, which the tests check at and around every step
// and on random values (and which held for all 1,065,353,217 floats in [0, 1] for both codes when this was written,
// 2026-12-04). Values outside [0, 1] take the reference's code of 0 (negative, -0, NaN) or of 1 (above 1, +inf): both
// codes clamp first.
#pragma once
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace ht::frame_io {

class Code8Table {
 public:
  using Reference = std::uint8_t (*)(float);
  // Builds the table from `reference`, which must be monotone non-decreasing on [0, 1] (about 8,000 calls) and take
  // no more than kStepsPerBucket steps in any bucket (std::invalid_argument otherwise).
  explicit Code8Table(Reference reference);

  std::uint8_t operator()(float x) const {
    std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
    // Above 1 and +inf -> 1; a set sign bit (negative, -0) and NaN -> 0: without branches, which random data
    // mispredicts.
    bits = bits > kOneBits ? (bits <= kInfinityBits ? kOneBits : 0u) : bits;
    std::uint32_t k = bucketCode_[bits >> kBucketShift];
    // At most kStepsPerBucket steps lie in a bucket (the constructor checks); stepBits_[256] is above every value.
    for (std::uint32_t s = 0; s < kStepsPerBucket; ++s) k += bits >= stepBits_[k + 1] ? 1u : 0u;
    return static_cast<std::uint8_t>(k);
  }

 private:
  static constexpr std::uint32_t kOneBits = 0x3F800000u, kInfinityBits = 0x7F800000u, kBucketShift = 16;
  static constexpr std::uint32_t kStepsPerBucket = 2;
  // stepBits_[k]: the bits of the smallest x in [0, 1] with code >= k (k >= 1); above 1.0f where the code never
  // reaches k; stepBits_[0] = 0 and stepBits_[256] = ~0.
  std::array<std::uint32_t, 257> stepBits_{};
  std::vector<std::uint8_t> bucketCode_;  // (kOneBits >> kBucketShift) + 1 buckets
};

}  // namespace ht::frame_io
