// srgb.h - the sRGB opto-electronic transfer function (IEC 61966-2-1) and 8-bit quantisation.
#pragma once
#include <cstdint>

namespace ht::cli {

// Linear value -> sRGB-encoded value in [0, 1]: 12.92*c for c <= 0.0031308, else 1.055*c^(1/2.4) - 0.055.
// The input is clamped to [0, 1] first; NaN maps to 0.
float srgbEncode(float linear);

// Linear value -> 8-bit sRGB code: round(255 * srgbEncode(linear)).
std::uint8_t srgbEncode8(float linear);

// Linear value (e.g. alpha) -> 8-bit code without a transfer curve: round(255 * clamp(v, 0, 1)), NaN -> 0.
std::uint8_t linearEncode8(float value);

}  // namespace ht::cli
