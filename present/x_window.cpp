// x_window.cpp - window creation (override-redirect or WM fullscreen), the invisible cursor, geometry queries.
#include "present/x_window.h"

#include <array>
#include <string>

namespace ht::present {
namespace {

// An invisible cursor: a 1x1 depth-1 pixmap with an empty mask as both shape and mask.
xcb_cursor_t invisibleCursor(const XConnection& x) {
  xcb_pixmap_t pixmap = xcb_generate_id(x.get());
  xcb_create_pixmap(x.get(), 1, pixmap, x.root(), 1, 1);
  xcb_cursor_t cursor = xcb_generate_id(x.get());
  xcb_create_cursor(x.get(), cursor, pixmap, pixmap, 0, 0, 0, 0, 0, 0, 0, 0);
  xcb_free_pixmap(x.get(), pixmap);
  return cursor;
}

// WM_NORMAL_HINTS (ICCCM 4.1.2.3): flags, x, y, width, height, then min/max/inc/aspect/base/gravity, 18 CARD32s.
void setPositionHints(const XConnection& x, xcb_window_t window, const Rect& rect) {
  constexpr std::uint32_t kUSPosition = 1, kUSSize = 2, kPMinSize = 16, kPMaxSize = 32;
  std::array<std::uint32_t, 18> hints{};
  hints[0] = kUSPosition | kUSSize | kPMinSize | kPMaxSize;
  hints[1] = static_cast<std::uint32_t>(rect.x);
  hints[2] = static_cast<std::uint32_t>(rect.y);
  hints[3] = hints[5] = hints[7] = rect.width;
  hints[4] = hints[6] = hints[8] = rect.height;
  xcb_change_property(x.get(), XCB_PROP_MODE_REPLACE, window, XCB_ATOM_WM_NORMAL_HINTS, XCB_ATOM_WM_SIZE_HINTS, 32,
                      hints.size(), hints.data());
}

void requestFullscreen(const XConnection& x, xcb_window_t window) {
  xcb_atom_t state = x.atom("_NET_WM_STATE"), fullscreen = x.atom("_NET_WM_STATE_FULLSCREEN");
  xcb_change_property(x.get(), XCB_PROP_MODE_REPLACE, window, state, XCB_ATOM_ATOM, 32, 1, &fullscreen);
}

void setTitle(const XConnection& x, xcb_window_t window) {
  const std::string title = "holotrace panel";
  xcb_change_property(x.get(), XCB_PROP_MODE_REPLACE, window, XCB_ATOM_WM_NAME, XCB_ATOM_STRING, 8,
                      static_cast<std::uint32_t>(title.size()), title.data());
}

}  // namespace

XWindow::XWindow(const XConnection& x, const Rect& rect, WindowMode mode) : x_(x) {
  if (!x.alive()) throw PresentError("X display '" + x.name() + "' is gone");
  cursor_ = invisibleCursor(x);
  window_ = xcb_generate_id(x.get());
  // Value order follows the mask bits: back pixel, override-redirect, event mask, cursor.
  const std::uint32_t mask = XCB_CW_BACK_PIXEL | XCB_CW_OVERRIDE_REDIRECT | XCB_CW_EVENT_MASK | XCB_CW_CURSOR;
  const std::array<std::uint32_t, 4> values = {x.screen()->black_pixel, mode == WindowMode::OverrideRedirect ? 1u : 0u,
                                               XCB_EVENT_MASK_EXPOSURE | XCB_EVENT_MASK_STRUCTURE_NOTIFY, cursor_};
  auto cookie =
      xcb_create_window_checked(x.get(), XCB_COPY_FROM_PARENT, window_, x.root(), static_cast<std::int16_t>(rect.x),
                                static_cast<std::int16_t>(rect.y), static_cast<std::uint16_t>(rect.width),
                                static_cast<std::uint16_t>(rect.height), 0, XCB_WINDOW_CLASS_INPUT_OUTPUT,
                                x.screen()->root_visual, mask, values.data());
  if (xcb_generic_error_t* error = xcb_request_check(x.get(), cookie)) {
    int code = error->error_code;
    std::free(error);
    xcb_free_cursor(x.get(), cursor_);
    throw PresentError("X display '" + x.name() + "': cannot create a window at " + describeRect(rect) + " (X error " +
                       std::to_string(code) + ")");
  }
  setTitle(x, window_);
  if (mode == WindowMode::Fullscreen) {
    setPositionHints(x, window_, rect);
    requestFullscreen(x, window_);
  }
  xcb_map_window(x.get(), window_);
  place(rect);
}

XWindow::~XWindow() {
  if (x_.alive()) {
    xcb_destroy_window(x_.get(), window_);
    xcb_free_cursor(x_.get(), cursor_);
    xcb_flush(x_.get());
  }
}

void XWindow::place(const Rect& rect) {
  const std::array<std::uint32_t, 5> values = {static_cast<std::uint32_t>(rect.x), static_cast<std::uint32_t>(rect.y),
                                               rect.width, rect.height, XCB_STACK_MODE_ABOVE};
  xcb_configure_window(x_.get(), window_,
                       XCB_CONFIG_WINDOW_X | XCB_CONFIG_WINDOW_Y | XCB_CONFIG_WINDOW_WIDTH | XCB_CONFIG_WINDOW_HEIGHT |
                           XCB_CONFIG_WINDOW_STACK_MODE,
                       values.data());
  xcb_flush(x_.get());
}

Rect XWindow::geometry() const {
  XReply<xcb_get_geometry_reply_t> g(xcb_get_geometry_reply(x_.get(), xcb_get_geometry(x_.get(), window_), nullptr));
  XReply<xcb_translate_coordinates_reply_t> t(xcb_translate_coordinates_reply(
      x_.get(), xcb_translate_coordinates(x_.get(), window_, x_.root(), 0, 0), nullptr));
  if (!g || !t) throw PresentError("X display '" + x_.name() + "': window geometry unavailable");
  return Rect{t->dst_x, t->dst_y, g->width, g->height};
}

bool XWindow::overrideRedirect() const {
  XReply<xcb_get_window_attributes_reply_t> a(
      xcb_get_window_attributes_reply(x_.get(), xcb_get_window_attributes(x_.get(), window_), nullptr));
  return a && a->override_redirect;
}

}  // namespace ht::present
