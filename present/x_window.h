// x_window.h - the window a panel's frames are shown in: exactly the monitor's rectangle at its origin, 1:1 pixels,
// no decoration, no cursor. Override-redirect by default (the window manager neither moves, decorates nor stacks it,
// so it lands exactly where asked); WindowMode::Fullscreen instead asks the window manager for fullscreen
// (_NET_WM_STATE_FULLSCREEN, with USPosition|USSize hints so it picks the right monitor).
#pragma once
#include <xcb/xcb.h>

#include "present/randr_snapshot.h"
#include "present/x_connection.h"

namespace ht::present {

enum class WindowMode { OverrideRedirect, Fullscreen };

class XWindow {
 public:
  // Creates and maps the window. Throws PresentError.
  XWindow(const XConnection& x, const Rect& rect, WindowMode mode);
  ~XWindow();
  XWindow(const XWindow&) = delete;
  XWindow& operator=(const XWindow&) = delete;

  xcb_window_t id() const { return window_; }
  // Puts the window back on `rect` and on top (cheap; done after re-attaching and on request).
  void place(const Rect& rect);
  // Where the window is on the root window now, as the server says.
  Rect geometry() const;
  // True if the window has the override-redirect attribute.
  bool overrideRedirect() const;

 private:
  const XConnection& x_;
  xcb_window_t window_ = XCB_NONE;
  xcb_cursor_t cursor_ = XCB_NONE;
};

}  // namespace ht::present
