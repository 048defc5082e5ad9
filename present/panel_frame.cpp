// panel_frame.cpp - rendered frame -> panel bytes through frame_io's own mosaic and 8-bit encoding, so the panel
// shows exactly the file sink's PNG.
#include "present/panel_frame.h"

#include "common/error.h"
#include "frame_io/pixel_encoding.h"
#include "frame_io/view_mosaic.h"

namespace ht::present {

PanelFrame panelFrame(const frame_io::FrameImages& frame, const frame_io::FrameDisplay& display) {
  frame_io::checkFrame(frame, "panel frame");
  PanelFrame out;
  if (!panelImageIsTheFrame(frame, display)) {
    const frame_io::RgbaImage image = frame_io::mosaicImage(frame, display.quilt);
    out.width = image.width;
    out.height = image.height;
    out.rgba = frame_io::encodeRgba8Srgb(image.rgba);
  } else {  // the mosaic is the frame's own pixels: encoded without a copy
    out.width = frame.width;
    out.height = frame.height * frame.views;
    out.rgba = frame_io::encodeRgba8Srgb(frame.rgba);
  }
  out.done = Clock::now();
  return out;
}

bool panelImageIsTheFrame(const frame_io::FrameImages& frame, const frame_io::FrameDisplay& display) {
  return frame.views <= 1 || !display.quilt;
}

PanelFrame panelFrameFromRgba8(const frame_io::FrameImages& frame, std::span<const std::uint8_t> rgba8) {
  frame_io::checkFrame(frame, "panel frame");
  if (rgba8.size() != frame.rgba.size()) {
    throw ht::IoError("panel frame: " + std::to_string(rgba8.size()) + " RGBA8 bytes for a frame of " +
                      std::to_string(frame.rgba.size()) + " values");
  }
  PanelFrame out;
  out.width = frame.width;
  out.height = frame.height * frame.views;
  out.rgba.assign(rgba8.begin(), rgba8.end());
  out.done = Clock::now();
  return out;
}

}  // namespace ht::present
