// srgb.cpp - see srgb.h.
#include "cli/srgb.h"

#include <cmath>

#include "common/srgb.h"

namespace ht::cli {
namespace {

std::uint8_t quantize8(float unit) { return static_cast<std::uint8_t>(std::lround(unit * 255.0f)); }

}  // namespace

float srgbEncode(float linear) { return gpu_shared::ht_srgb_encode(linear); }

std::uint8_t srgbEncode8(float linear) { return quantize8(srgbEncode(linear)); }

std::uint8_t linearEncode8(float value) { return quantize8(gpu_shared::ht_clamp_unit(value)); }

}  // namespace ht::cli
