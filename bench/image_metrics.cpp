// image_metrics.cpp - see image_metrics.h.
#include "bench/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/srgb.h"

namespace ht::bench {
namespace {

constexpr int kRadius = 5;  // 11 taps
constexpr double kSigma = 1.5;
constexpr double kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;

// One channel of the image, sRGB-encoded (the encoding PNG output and the refinement kernel use, common/srgb.h), as
// doubles for the sums.
std::vector<double> channel(std::span<const float> rgba, std::size_t pixels, int c) {
  std::vector<double> out(pixels);
  for (std::size_t i = 0; i < pixels; ++i) out[i] = gpu_shared::ht_srgb_encode(rgba[4 * i + c]);
  return out;
}

std::vector<double> gaussianWeights() {
  std::vector<double> w(2 * kRadius + 1);
  double sum = 0.0;
  for (int k = -kRadius; k <= kRadius; ++k) sum += w[k + kRadius] = std::exp(-k * k / (2.0 * kSigma * kSigma));
  for (double& v : w) v /= sum;
  return w;
}

// Separable Gaussian blur with clamped borders.
std::vector<double> blur(const std::vector<double>& in, std::uint32_t w, std::uint32_t h) {
  static const std::vector<double> weights = gaussianWeights();
  std::vector<double> tmp(in.size()), out(in.size());
  for (std::uint32_t y = 0; y < h; ++y) {
    for (std::uint32_t x = 0; x < w; ++x) {
      double s = 0.0;
      for (int k = -kRadius; k <= kRadius; ++k)
        s += weights[k + kRadius] * in[std::size_t(y) * w + std::clamp<int>(int(x) + k, 0, int(w) - 1)];
      tmp[std::size_t(y) * w + x] = s;
    }
  }
  for (std::uint32_t y = 0; y < h; ++y) {
    for (std::uint32_t x = 0; x < w; ++x) {
      double s = 0.0;
      for (int k = -kRadius; k <= kRadius; ++k)
        s += weights[k + kRadius] * tmp[std::size_t(std::clamp<int>(int(y) + k, 0, int(h) - 1)) * w + x];
      out[std::size_t(y) * w + x] = s;
    }
  }
  return out;
}

std::vector<double> product(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> out(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) out[i] = a[i] * b[i];
  return out;
}

double meanSsim(const std::vector<double>& a, const std::vector<double>& b, std::uint32_t w, std::uint32_t h) {
  const auto muA = blur(a, w, h), muB = blur(b, w, h);
  const auto aa = blur(product(a, a), w, h), bb = blur(product(b, b), w, h), ab = blur(product(a, b), w, h);
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double varA = aa[i] - muA[i] * muA[i], varB = bb[i] - muB[i] * muB[i], cov = ab[i] - muA[i] * muB[i];
    sum += ((2 * muA[i] * muB[i] + kC1) * (2 * cov + kC2)) /
           ((muA[i] * muA[i] + muB[i] * muB[i] + kC1) * (varA + varB + kC2));
  }
  return sum / double(a.size());
}

}  // namespace

double psnrFromMse(double mse) { return mse > 0.0 ? -10.0 * std::log10(mse) : std::numeric_limits<double>::infinity(); }

ImageMetrics compareImages(std::span<const float> test, std::span<const float> reference, std::uint32_t width,
                           std::uint32_t height) {
  const std::size_t pixels = std::size_t(width) * height;
  if (test.size() != 4 * pixels || reference.size() != 4 * pixels) {
    throw Error("compareImages: images of " + std::to_string(test.size() / 4) + " and " +
                std::to_string(reference.size() / 4) + " pixels, expected " + std::to_string(pixels));
  }
  ImageMetrics m;
  double ssimSum = 0.0, squared = 0.0;
  for (int c = 0; c < 3; ++c) {
    const auto a = channel(test, pixels, c), b = channel(reference, pixels, c);
    for (std::size_t i = 0; i < pixels; ++i) squared += (a[i] - b[i]) * (a[i] - b[i]);
    ssimSum += meanSsim(a, b, width, height);
  }
  m.mse = squared / double(3 * pixels);
  m.rmse = std::sqrt(m.mse);
  m.psnrDb = psnrFromMse(m.mse);
  m.ssim = ssimSum / 3.0;
  return m;
}

double changedValueFraction(std::span<const float> a, std::span<const float> b) {
  if (a.size() != b.size()) {
    throw Error("changedValueFraction: frames of " + std::to_string(a.size()) + " and " + std::to_string(b.size()) +
                " values");
  }
  std::size_t changed = 0, values = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (i % 4 == 3) continue;
    ++values;
    changed += a[i] != b[i] ? 1 : 0;
  }
  return values ? double(changed) / double(values) : 0.0;
}

}  // namespace ht::bench
