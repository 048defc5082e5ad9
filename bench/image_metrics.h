// image_metrics.h - full-reference image error: RMSE, PSNR and SSIM of a test image against a reference.
//
// Both images are linear RGBA float (RenderResult layout); the metrics are computed on DISPLAY-REFERRED values:
// each RGB channel clamped to [0, 1] and sRGB-encoded in float (common/srgb.h, as PNG output), i.e. what the panel
// shows. Peak = 1.
//   RMSE = sqrt(mean over pixels and R, G, B of (a - b)^2);  PSNR = -10 log10(MSE)
//   SSIM (Wang, Bovik, Sheikh, Simoncelli 2004): 11-tap Gaussian window, sigma 1.5, K1 = 0.01, K2 = 0.03, per
//   channel, mean over all window positions (borders clamped) and the three channels.
#pragma once
#include <cstdint>
#include <span>

namespace ht::bench {

struct ImageMetrics {
  double mse = 0.0, rmse = 0.0, psnrDb = 0.0, ssim = 0.0;
};

// PSNR in dB of a mean squared error on the [0, 1] scale (+inf for 0).
double psnrFromMse(double mse);

// Throws ht::Error if the sizes differ from width * height * 4.
ImageMetrics compareImages(std::span<const float> test, std::span<const float> reference, std::uint32_t width,
                           std::uint32_t height);

// Fraction of the RGB values (alpha skipped) of two RGBA frames that differ at all; 0 for empty frames. Throws
// ht::Error if the sizes differ.
double changedValueFraction(std::span<const float> a, std::span<const float> b);

}  // namespace ht::bench
