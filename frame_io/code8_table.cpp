// code8_table.cpp - see code8_table.h.
#include "frame_io/code8_table.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ht::frame_io {

Code8Table::Code8Table(Reference reference) : bucketCode_((kOneBits >> kBucketShift) + 1) {
  const auto code = [&](std::uint32_t bits) { return reference(std::bit_cast<float>(bits)); };
  stepBits_[0] = 0;
  stepBits_[256] = ~0u;
  for (std::uint32_t k = 1; k <= 255; ++k) {
    if (code(kOneBits) < k) {  // never reached on [0, 1]
      stepBits_[k] = kOneBits + 1;
      continue;
    }
    std::uint32_t lo = 0, hi = kOneBits;  // invariant: code(hi) >= k; find the least such bits
    while (lo < hi) {
      const std::uint32_t mid = lo + (hi - lo) / 2;
      if (code(mid) >= k) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
    stepBits_[k] = lo;
  }
  std::uint32_t k = 0;  // buckets ascend, and so do their codes
  for (std::uint32_t b = 0; b < bucketCode_.size(); ++b) {
    const std::uint32_t first = b << kBucketShift;
    while (k < 255 && first >= stepBits_[k + 1]) ++k;
    bucketCode_[b] = static_cast<std::uint8_t>(k);
    // The steps inside the bucket: what operator() adds to its first value's code.
    const std::uint32_t next = std::min(first + (1u << kBucketShift), kOneBits + 1);
    std::uint32_t steps = 0;
    while (k + steps < 255 && stepBits_[k + steps + 1] < next) ++steps;
    if (steps > kStepsPerBucket) {
      throw std::invalid_argument("Code8Table: " + std::to_string(steps) + " code steps between float bits " +
                                  std::to_string(first) + " and " + std::to_string(next) + " (at most " +
                                  std::to_string(kStepsPerBucket) + ")");
    }
  }
}

}  // namespace ht::frame_io
