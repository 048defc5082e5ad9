// pixel_encoding.cpp - see pixel_encoding.h.
#include "frame_io/pixel_encoding.h"

#include <Imath/half.h>

#include <bit>
#include <cmath>
#include <cstring>

#include "common/srgb.h"

namespace ht::frame_io {
namespace {

std::uint8_t quantize8(float unit) { return static_cast<std::uint8_t>(std::lround(unit * 255.0f)); }

}  // namespace

std::uint8_t srgbEncode8(float linear) { return quantize8(gpu_shared::ht_srgb_encode(linear)); }

std::uint8_t linearEncode8(float value) { return quantize8(gpu_shared::ht_clamp_unit(value)); }

float srgbDecode8(std::uint8_t code) { return gpu_shared::ht_srgb_decode(float(code) / 255.0f); }

std::vector<std::uint8_t> encodeRgba8Srgb(std::span<const float> rgba) {
  std::vector<std::uint8_t> out(rgba.size());
  for (std::size_t i = 0; i < rgba.size(); ++i) out[i] = i % 4 == 3 ? linearEncode8(rgba[i]) : srgbEncode8(rgba[i]);
  return out;
}

std::vector<std::uint8_t> encodeRgba16fLinear(std::span<const float> rgba) {
  static_assert(std::endian::native == std::endian::little, "RGBA16F is little endian on the wire");
  std::vector<std::uint8_t> out(rgba.size() * 2);
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    const std::uint16_t bits = Imath::half(rgba[i]).bits();
    std::memcpy(out.data() + 2 * i, &bits, 2);
  }
  return out;
}

}  // namespace ht::frame_io
