// panel_frame.h - one frame for the panel: the 8-bit sRGB RGBA pixels (row 0 = top) that the file sink writes as PNG
// for the same frame (frame_io/pixel_encoding.h), with when rendering finished (for the render-to-photon latency).
#pragma once
#include <chrono>
#include <cstdint>
#include <span>
#include <vector>

#include "frame_io/frame_package.h"

namespace ht::present {

using Clock = std::chrono::steady_clock;

struct PanelFrame {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes, colour sRGB-encoded, alpha linear
  std::uint64_t sequence = 0;      // set by the mailbox: 1, 2, ... in submission order
  Clock::time_point done{};        // when the frame was complete (set by the caller, default: on submission)
};

// The panel image of a rendered frame: the same pixels as the PNG frame_io::encodeMosaicPng writes (a one-view frame
// itself, else the quilt or the stacked views). Throws IoError for a frame whose pixels do not match its size.
PanelFrame panelFrame(const frame_io::FrameImages& frame, const frame_io::FrameDisplay& display);

// Whether the panel image of `frame` is the frame's own pixels (one view, or the views stacked top to bottom, as the
// raw RGBA8 format carries them); false when its views form a quilt.
bool panelImageIsTheFrame(const frame_io::FrameImages& frame, const frame_io::FrameDisplay& display);

// The panel frame of `frame` from its RGBA8 bytes (frame_io::encodeRgba8Srgb of frame.rgba, e.g. what a stream
// sends), copied instead of encoded again. panelImageIsTheFrame must hold; IoError if the sizes do not match.
PanelFrame panelFrameFromRgba8(const frame_io::FrameImages& frame, std::span<const std::uint8_t> rgba8);

}  // namespace ht::present
