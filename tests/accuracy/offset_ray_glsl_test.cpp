// ht_offset_ray (bvh/offset_ray.h) gives the same bits in GLSL (run by gpu/shaders/offset_ray_probe.comp on the test
// device) as in C++. Both builds must round identically: C++ is compiled with -ffp-contract=off and the GLSL marks the
// near-zero branch `p + 1/65536 * n` HT_PRECISE (`precise`), so neither side may fuse it into an FMA. The inputs cover
// magnitudes 1e-30 ... 1e30 of both signs with random unit normals, plus the branch boundary |p| = 1/32, zeros,
// denormals and the largest finite floats.
// Is `precise` what makes the two builds equal? No: the near-zero branch multiplies n by 1/65536, a power of two, so
// the product is exact (it cannot underflow for |n| >= 2^-110) and p + s*n is rounded once whether or not it is fused
// into an FMA. The integer branch uses exact 256*n and bit arithmetic. The test checks this claim on every input
// (fma(s, n, p) == p + s*n) instead of assuming it; what remains to differ is branch selection at |p| = 1/32, the
// float->int truncation, NaN/Inf bit patterns from the integer step, and denormal flushing on the device.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "accuracy_test_util.h"
#include "bvh/offset_ray.h"
#include "gpu/kernel_probe.h"

namespace ht::accuracy {
namespace {

using gpu::OffsetRayProbeInput;

glm::vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (;;) {
    const glm::vec3 v(g(rng), g(rng), g(rng));
    const float len = glm::length(v);
    if (len > 1e-3f) return v / len;
  }
}

// sign * 10^U(-30, 30), drawn per component.
float randomMagnitude(std::mt19937& rng) {
  std::uniform_real_distribution<float> exponent(-30.0f, 30.0f);
  std::bernoulli_distribution negative(0.5);
  const float m = std::pow(10.0f, exponent(rng));
  return negative(rng) ? -m : m;
}

std::vector<OffsetRayProbeInput> probeInputs(std::uint32_t randomCount) {
  std::mt19937 rng(20261122);
  std::vector<OffsetRayProbeInput> in;
  for (std::uint32_t i = 0; i < randomCount; ++i)
    in.push_back({glm::vec3(randomMagnitude(rng), randomMagnitude(rng), randomMagnitude(rng)), randomUnit(rng)});
  // Edge values on every component, each with a few random normals.
  const float edges[] = {0.0f,
                         -0.0f,
                         gpu_shared::HT_OFFSET_ORIGIN,
                         -gpu_shared::HT_OFFSET_ORIGIN,
                         std::nextafter(gpu_shared::HT_OFFSET_ORIGIN, 0.0f),
                         std::nextafter(-gpu_shared::HT_OFFSET_ORIGIN, 0.0f),
                         std::numeric_limits<float>::denorm_min(),
                         -std::numeric_limits<float>::min(),
                         std::numeric_limits<float>::max(),
                         -std::numeric_limits<float>::max(),
                         1e-30f,
                         -1e30f};
  for (float e : edges)
    for (int k = 0; k < 8; ++k) in.push_back({glm::vec3(e, -e, e), randomUnit(rng)});
  // Denormal points with zero normal components: p + 0 must stay the same denormal (a device that flushes denormals
  // would return 0 here).
  for (float d : {std::numeric_limits<float>::denorm_min(), -3e-40f, 1e-39f})
    in.push_back({glm::vec3(d, -d, d), glm::vec3(0.0f, 0.0f, 0.0f)});
  // Axis-aligned normals (int(256 * n) = 256 exactly) and tiny normal components (int(256 * n) = 0).
  for (int k = 0; k < 64; ++k) {
    const glm::vec3 p(randomMagnitude(rng), randomMagnitude(rng), randomMagnitude(rng));
    in.push_back({p, glm::vec3(0.0f, 0.0f, k % 2 ? 1.0f : -1.0f)});
    in.push_back({p, glm::normalize(glm::vec3(1e-4f, 1.0f, -1e-3f))});
  }
  return in;
}

// The near-zero branch as a contracting compiler would evaluate it: fma(1/65536, n, p).
float fusedComponent(float p, float n) {
  return std::fabs(p) < gpu_shared::HT_OFFSET_ORIGIN ? std::fma(gpu_shared::HT_OFFSET_FLOAT_SCALE, n, p)
                                                     : gpu_shared::ht_offset_component(p, n);
}

TEST(OffsetRayGlsl, GpuAndCppAgreeInEveryBit) {
  const auto inputs = probeInputs(test::scaledCount(200000));
  const std::vector<glm::vec3> gpu = gpu::runOffsetRayProbe(test::sharedContext(), inputs);
  ASSERT_EQ(gpu.size(), inputs.size());
  std::uint64_t mismatches = 0, fmaSensitive = 0, nearZeroBranch = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec3 cpu = gpu_shared::ht_offset_ray(inputs[i].p, inputs[i].n);
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t want = std::bit_cast<std::uint32_t>(cpu[c]);
      const std::uint32_t got = std::bit_cast<std::uint32_t>(gpu[i][c]);
      if (want != got && ++mismatches <= 10)
        ADD_FAILURE() << "input " << i << " component " << c << ": p " << inputs[i].p[c] << " n " << inputs[i].n[c]
                      << ": C++ 0x" << std::hex << want << " GLSL 0x" << got;
      const bool nearZero = std::fabs(inputs[i].p[c]) < gpu_shared::HT_OFFSET_ORIGIN;
      nearZeroBranch += nearZero ? 1 : 0;
      fmaSensitive += std::bit_cast<std::uint32_t>(fusedComponent(inputs[i].p[c], inputs[i].n[c])) != want ? 1 : 0;
    }
  }
  std::printf(
      "offset_ray GLSL vs C++: %zu inputs (%zu components, %llu in the |p| < 1/32 branch), %llu bit mismatches; "
      "components where fma(1/65536, n, p) != p + n/65536: %llu\n",
      inputs.size(), 3 * inputs.size(), (unsigned long long)nearZeroBranch, (unsigned long long)mismatches,
      (unsigned long long)fmaSensitive);
  EXPECT_EQ(mismatches, 0u);
  // The exact-product argument above: contraction cannot change ht_offset_ray's result.
  EXPECT_EQ(fmaSensitive, 0u);
}

}  // namespace
}  // namespace ht::accuracy
