// screen_capture.cpp - xcb_get_image of the root window, 32-bit pixels with the visual's channel masks -> RGB.
#include "present/screen_capture.h"

#include <bit>
#include <cstring>

namespace ht::present {
namespace {

const xcb_visualtype_t* rootVisual(const XConnection& x) {
  for (auto d = xcb_screen_allowed_depths_iterator(x.screen()); d.rem; xcb_depth_next(&d)) {
    for (auto v = xcb_depth_visuals_iterator(d.data); v.rem; xcb_visualtype_next(&v)) {
      if (v.data->visual_id == x.screen()->root_visual) return v.data;
    }
  }
  return nullptr;
}

std::uint8_t channel(std::uint32_t pixel, std::uint32_t mask) {
  return static_cast<std::uint8_t>((pixel & mask) >> std::countr_zero(mask));
}

}  // namespace

std::vector<std::uint8_t> captureRgb(const XConnection& x, const Rect& rect) {
  const xcb_visualtype_t* visual = rootVisual(x);
  if (!visual || visual->_class != XCB_VISUAL_CLASS_TRUE_COLOR || visual->bits_per_rgb_value != 8) {
    throw PresentError("X display '" + x.name() + "': screen capture needs an 8-bit-per-channel TrueColor root");
  }
  auto cookie = xcb_get_image(x.get(), XCB_IMAGE_FORMAT_Z_PIXMAP, x.root(), static_cast<std::int16_t>(rect.x),
                              static_cast<std::int16_t>(rect.y), static_cast<std::uint16_t>(rect.width),
                              static_cast<std::uint16_t>(rect.height), ~0u);
  XReply<xcb_get_image_reply_t> image(xcb_get_image_reply(x.get(), cookie, nullptr));
  const std::size_t pixels = std::size_t(rect.width) * rect.height;
  if (!image || std::size_t(xcb_get_image_data_length(image.get())) < pixels * 4) {
    throw PresentError("X display '" + x.name() + "': cannot read back " + describeRect(rect) + " of the screen");
  }
  const std::uint8_t* data = xcb_get_image_data(image.get());
  std::vector<std::uint8_t> rgb(pixels * 3);
  for (std::size_t i = 0; i < pixels; ++i) {
    std::uint32_t pixel;
    std::memcpy(&pixel, data + 4 * i, 4);  // the server sends our byte order
    rgb[3 * i] = channel(pixel, visual->red_mask);
    rgb[3 * i + 1] = channel(pixel, visual->green_mask);
    rgb[3 * i + 2] = channel(pixel, visual->blue_mask);
  }
  return rgb;
}

}  // namespace ht::present
