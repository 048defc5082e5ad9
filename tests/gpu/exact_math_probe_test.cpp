// exact_math_probe_test.cpp - ht_div, ht_div3 and ht_sqrt (common/exact_division.h) on the test device give the bits
// of C++'s `/` and std::sqrt, also where the exact result lies closest to the midpoint of two floats, where a driver's
// approximate division or square root (Vulkan allows several ULP) would round the other way: docs/DRIVERS.md.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "gpu/kernel_probe.h"
#include "gpu_test_util.h"

namespace ht::test {
namespace {

float nextUp(float v) { return std::nextafter(v, std::numeric_limits<float>::infinity()); }

// sign * 10^U(-30, 30).
float randomMagnitude(std::mt19937& rng) {
  std::uniform_real_distribution<float> exponent(-30.0f, 30.0f);
  std::bernoulli_distribution negative(0.5);
  const float v = std::pow(10.0f, exponent(rng));
  return negative(rng) ? -v : v;
}

// Inputs (a, b, x, 0): random magnitudes; quotients and roots as close to a float midpoint as float inputs allow
// (a = the float nearest to m * b and x = the float nearest to m * m, for m the midpoint above a random float);
// zeros, infinities, denormals and the largest floats.
std::vector<glm::vec4> probeInputs() {
  std::mt19937 rng(20261204);
  std::vector<glm::vec4> in;
  std::uniform_real_distribution<float> unit(1.0f, 2.0f);
  for (int i = 0; i < 100000; ++i) {
    const float a = randomMagnitude(rng), b = randomMagnitude(rng);
    in.emplace_back(a, b, std::abs(randomMagnitude(rng)), 0.0f);
    const float s = unit(rng) * std::pow(2.0f, float(int(rng() % 64) - 32));
    const double m = 0.5 * (double(s) + double(nextUp(s)));  // the midpoint above s
    const float b2 = unit(rng);
    in.emplace_back(float(m * double(b2)), b2, float(m * m), 0.0f);
  }
  const float big = std::numeric_limits<float>::max(), tiny = std::numeric_limits<float>::denorm_min();
  for (float a : {0.0f, -0.0f, 1.0f, 3.0f, big, tiny, 1e-38f}) {
    for (float b : {1.0f, 3.0f, 7.0f, big, tiny, 1e-38f, -2.5f}) in.emplace_back(a, b, std::abs(a) + std::abs(b), 0.0f);
  }
  in.emplace_back(1.0f, 0.0f, std::numeric_limits<float>::infinity(), 0.0f);
  return in;
}

bool sameBits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

TEST(ExactMathProbe, DivisionAndSquareRootGiveTheBitsOfCpp) {
  const std::vector<glm::vec4> in = probeInputs();
  const std::vector<glm::vec4> out = gpu::runExactMathProbe(sharedContext(), in);
  ASSERT_EQ(out.size(), in.size());
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const float a = in[i].x, b = in[i].y, x = in[i].z;
    const float div = a / b, root = std::sqrt(x), div3 = x / b;
    const bool ok = sameBits(out[i].x, div) && sameBits(out[i].y, root) && sameBits(out[i].z, div3);
    if (!ok && ++wrong <= 8) {
      ADD_FAILURE() << "input " << i << ": a " << a << " b " << b << " x " << x << ": GPU " << out[i].x << " "
                    << out[i].y << " " << out[i].z << ", C++ " << div << " " << root << " " << div3;
    }
  }
  std::printf("exact math probe on %s: %zu inputs, %zu differ from C++\n", sharedContext().device().name.c_str(),
              in.size(), wrong);
  EXPECT_EQ(wrong, 0u);
}

}  // namespace
}  // namespace ht::test
