// screen_capture.h - the pixels of a rectangle of an X screen as RGB bytes (xcb_get_image on the root window, Z
// pixmap): what the panel shows. Tests compare it with the frame's PNG; the benchmark watches for a frame to appear.
#pragma once
#include <cstdint>
#include <vector>

#include "present/randr_snapshot.h"
#include "present/x_connection.h"

namespace ht::present {

// width * height * 3 bytes (R, G, B), row 0 = top. Needs a 24/32-bit TrueColor root (PresentError otherwise).
std::vector<std::uint8_t> captureRgb(const XConnection& x, const Rect& rect);

}  // namespace ht::present
