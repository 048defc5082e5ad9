// pixel_encoding.cpp - see pixel_encoding.h.
#include "frame_io/pixel_encoding.h"

#include <Imath/half.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "common/srgb.h"
#include "frame_io/code8_table.h"

namespace ht::frame_io {
namespace {

std::uint8_t quantize8(float unit) { return static_cast<std::uint8_t>(std::lround(unit * 255.0f)); }

}  // namespace

std::uint8_t srgbEncode8(float linear) { return quantize8(gpu_shared::ht_srgb_encode(linear)); }

std::uint8_t linearEncode8(float value) { return quantize8(gpu_shared::ht_clamp_unit(value)); }

float srgbDecode8(std::uint8_t code) { return gpu_shared::ht_srgb_decode(float(code) / 255.0f); }

void encodeRgba8Srgb(std::span<const float> rgba, std::span<std::uint8_t> out) {
  if (out.size() != rgba.size() || rgba.size() % 4 != 0) {
    throw std::invalid_argument("encodeRgba8Srgb: " + std::to_string(rgba.size()) + " floats into " +
                                std::to_string(out.size()) + " bytes (want a multiple of 4, one byte per float)");
  }
  // The codes' tables, built at the first call (thread-safe static initialisation) and constant after it.
  static const Code8Table srgb(srgbEncode8), alpha(linearEncode8);
  const auto encodePixels = [&](std::size_t first, std::size_t end) {
    for (std::size_t i = 4 * first; i < 4 * end; i += 4) {
      out[i] = srgb(rgba[i]);
      out[i + 1] = srgb(rgba[i + 1]);
      out[i + 2] = srgb(rgba[i + 2]);
      out[i + 3] = alpha(rgba[i + 3]);
    }
  };
  // A panel image (1536 x 2048) takes 55 ms on one core of the 2-vCPU EPYC, 32-40 ms on both (docs/BENCHMARKS.md
  // "Encoding frames"), so large frames are cut across up to kMaxEncodeThreads threads of kPixelsPerThread pixels
  // or more.
  constexpr std::size_t kPixelsPerThread = 1u << 18, kMaxEncodeThreads = 8;
  const std::size_t pixels = rgba.size() / 4;
  const std::size_t threads = std::clamp<std::size_t>(
      std::min<std::size_t>(pixels / kPixelsPerThread, std::thread::hardware_concurrency()), 1, kMaxEncodeThreads);
  const std::size_t per = (pixels + threads - 1) / threads;
  std::vector<std::jthread> workers;
  std::size_t next = per;  // the calling thread takes [0, per)
  try {
    for (; next < pixels; next += per) workers.emplace_back(encodePixels, next, std::min(pixels, next + per));
  } catch (const std::system_error&) {  // no thread to be had: the rest on this one
    encodePixels(next, pixels);
  }
  encodePixels(0, std::min(per, pixels));
}  // the workers join here

std::vector<std::uint8_t> encodeRgba8Srgb(std::span<const float> rgba) {
  std::vector<std::uint8_t> out(rgba.size());
  encodeRgba8Srgb(rgba, out);
  return out;
}

void encodeRgba16fLinear(std::span<const float> rgba, std::span<std::uint8_t> out) {
  static_assert(std::endian::native == std::endian::little, "RGBA16F is little endian on the wire");
  if (out.size() != 2 * rgba.size()) {
    throw std::invalid_argument("encodeRgba16fLinear: " + std::to_string(rgba.size()) + " floats into " +
                                std::to_string(out.size()) + " bytes (want two bytes per float)");
  }
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    const std::uint16_t bits = Imath::half(rgba[i]).bits();
    std::memcpy(out.data() + 2 * i, &bits, 2);
  }
}

std::vector<std::uint8_t> encodeRgba16fLinear(std::span<const float> rgba) {
  std::vector<std::uint8_t> out(rgba.size() * 2);
  encodeRgba16fLinear(rgba, out);
  return out;
}

}  // namespace ht::frame_io
