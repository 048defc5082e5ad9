// pixel_encoding.h - linear float RGBA (row 0 = top) as 8-bit and half-float codes: the raw pixel formats of the
// daemon's frames (RGBA8, RGBA16F), the 8-bit panel image of a display, and the pixels of PNG files.
//
// 8-bit: colour through the sRGB OETF (common/srgb.h), alpha linear; both clamped to [0, 1] (NaN -> 0) and rounded to
// the nearest code, round(255 * v). Half: IEEE 754 binary16, round to nearest even, little endian.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace ht::frame_io {

// Linear value -> 8-bit sRGB code.
std::uint8_t srgbEncode8(float linear);

// Linear value (alpha) -> 8-bit code without a transfer curve.
std::uint8_t linearEncode8(float value);

// 8-bit sRGB code -> linear value: decoding then encoding gives the code back for all 256 codes.
float srgbDecode8(std::uint8_t code);

// RGBA floats -> RGBA bytes (colour sRGB, alpha linear), one byte per float: the codes of srgbEncode8 and
// linearEncode8, looked up (frame_io/code8_table.h).
std::vector<std::uint8_t> encodeRgba8Srgb(std::span<const float> rgba);
// The same into `out` (as many bytes as floats, a multiple of 4; std::invalid_argument otherwise).
void encodeRgba8Srgb(std::span<const float> rgba, std::span<std::uint8_t> out);

// RGBA floats -> little-endian half floats, two bytes per float, values unchanged (linear).
std::vector<std::uint8_t> encodeRgba16fLinear(std::span<const float> rgba);
// The same into `out` (two bytes per float; std::invalid_argument otherwise).
void encodeRgba16fLinear(std::span<const float> rgba, std::span<std::uint8_t> out);

}  // namespace ht::frame_io
