// panel_frame.cpp - rendered frame -> panel bytes through frame_io's own mosaic and 8-bit encoding, so the panel
// shows exactly the file sink's PNG.
#include "present/panel_frame.h"

#include "frame_io/pixel_encoding.h"
#include "frame_io/view_mosaic.h"

namespace ht::present {

PanelFrame panelFrame(const frame_io::FrameImages& frame, const frame_io::FrameDisplay& display) {
  frame_io::checkFrame(frame, "panel frame");
  PanelFrame out;
  if (frame.views > 1 && display.quilt) {
    const frame_io::RgbaImage image = frame_io::mosaicImage(frame, display.quilt);
    out.width = image.width;
    out.height = image.height;
    out.rgba = frame_io::encodeRgba8Srgb(image.rgba);
  } else {  // one view, or the views stacked: the mosaic is the frame's own pixels, encoded without a copy
    out.width = frame.width;
    out.height = frame.height * frame.views;
    out.rgba = frame_io::encodeRgba8Srgb(frame.rgba);
  }
  out.done = Clock::now();
  return out;
}

}  // namespace ht::present
