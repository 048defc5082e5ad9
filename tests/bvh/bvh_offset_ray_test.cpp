// bvh_offset_ray_test.cpp - Ray Tracing Gems ch. 6 offset_ray: constants, side and distance, and bit-exact
// agreement with a transcription of the chapter's int-based reference code.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "bvh/offset_ray.h"
#include "bvh_test_util.h"

namespace ht::bvh {
namespace {

using namespace gpu_shared;

TEST(BvhOffsetRay, ConstantsAreThoseOfTheChapter) {
  EXPECT_EQ(HT_OFFSET_ORIGIN, 1.0f / 32.0f);
  EXPECT_EQ(HT_OFFSET_FLOAT_SCALE, 1.0f / 65536.0f);
  EXPECT_NE(HT_OFFSET_FLOAT_SCALE, 1.0f / 65535.0f);  // a port seen in the wild used 1/65535 (docs/BVH.md §5.3)
  EXPECT_EQ(HT_OFFSET_INT_SCALE, 256.0f);
}

// The chapter's code with int arithmetic (in int64 here, so that -0.0's INT_MIN bits cannot overflow).
float chapterOffsetComponent(float p, float n) {
  int32_t ofi = static_cast<int32_t>(256.0f * n);
  int32_t bits;
  std::memcpy(&bits, &p, 4);
  int64_t moved = int64_t{bits} + (p < 0 ? -ofi : ofi);
  uint32_t movedBits = static_cast<uint32_t>(moved);
  float pi;
  std::memcpy(&pi, &movedBits, 4);
  return std::fabs(p) < 1.0f / 32.0f ? p + (1.0f / 65536.0f) * n : pi;
}

uint32_t bitsOf(float x) {
  uint32_t b;
  std::memcpy(&b, &x, 4);
  return b;
}

TEST(BvhOffsetRay, MagnitudesFrom1em30To1e30) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> exponent(-30.0f, 30.0f);
  std::bernoulli_distribution negative(0.5);
  const uint32_t count = 1u << 16;  // Falcor ComputeRayOrigin uses 2^16 points
  for (uint32_t i = 0; i < count; ++i) {
    glm::vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = (negative(rng) ? -1.0f : 1.0f) * std::pow(10.0f, exponent(rng));
    if (i % 97 == 0) p.y = (i % 2) ? 0.0f : -0.0f;
    glm::vec3 n = test::randomUnitVector(rng);
    glm::vec3 q = ht_offset_ray(p, n);
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(bitsOf(q[k]), bitsOf(chapterOffsetComponent(p[k], n[k]))) << "i " << i << " k " << k;
      ASSERT_TRUE(std::isfinite(q[k]));
      // Each component moves towards the sign of n (or stays, when |n| < 1/256 far from zero).
      double delta = double(q[k]) - double(p[k]);
      ASSERT_GE(delta * n[k], 0.0) << "i " << i << " k " << k;
      // Close: at most 256 ULPs (each <= 2^-23 max(|p|, |q|)) or n/65536 near zero.
      double bound =
          std::fabs(p[k]) < 1.0f / 32.0f
              ? std::fabs(n[k]) / 65536.0 + std::ldexp(std::fabs(double(q[k])), -23)  // + rounding of the sum
              : 256.0 * std::ldexp(std::max(std::fabs(double(p[k])), std::fabs(double(q[k]))), -23);
      ASSERT_LE(std::fabs(delta), bound) << "i " << i << " k " << k;
    }
    // Strictly on the normal's side of the plane through p.
    glm::dvec3 d = glm::dvec3(q) - glm::dvec3(p);
    ASSERT_GT(glm::dot(d, glm::dvec3(n)), 0.0) << "i " << i;
  }
}

TEST(BvhOffsetRay, OffsetPointIsOutsideAFarAwayPlane) {
  // Points on a tilted plane far from the origin: the offset point lies on the normal's side when
  // evaluated exactly in double (the purpose: the new ray does not re-hit the surface it leaves).
  std::mt19937 rng(77);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const glm::dvec3 normal = glm::normalize(glm::dvec3(0.3, -0.8, 0.52));
  const glm::dvec3 anchor(148376.0, 1234.0, -223423.0);
  glm::dvec3 u = glm::normalize(glm::cross(normal, glm::dvec3(1, 0, 0)));
  glm::dvec3 v = glm::cross(normal, u);
  for (int i = 0; i < 10000; ++i) {
    glm::vec3 p(anchor + 100.0 * double(unit(rng)) * u + 100.0 * double(unit(rng)) * v);
    double before = glm::dot(glm::dvec3(p) - anchor, normal);  // rounding puts p slightly off the plane
    glm::vec3 q = ht_offset_ray(p, glm::vec3(normal));
    double after = glm::dot(glm::dvec3(q) - anchor, normal);
    ASSERT_GT(after, std::max(before, 0.0)) << "i " << i;
  }
}

}  // namespace
}  // namespace ht::bvh
