// srgb.cpp - see srgb.h.
#include "cli/srgb.h"

#include <algorithm>
#include <cmath>

namespace ht::cli {
namespace {

float clampUnit(float v) { return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f); }

std::uint8_t quantize8(float unit) { return static_cast<std::uint8_t>(std::lround(unit * 255.0f)); }

}  // namespace

float srgbEncode(float linear) {
  const float c = clampUnit(linear);
  if (c <= 0.0031308f) return 12.92f * c;
  return std::min(1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f, 1.0f);
}

std::uint8_t srgbEncode8(float linear) { return quantize8(srgbEncode(linear)); }

std::uint8_t linearEncode8(float value) { return quantize8(clampUnit(value)); }

}  // namespace ht::cli
