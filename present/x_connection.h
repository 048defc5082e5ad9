// x_connection.h - one xcb connection to an X server (RAII), the root window of its default screen, and the errors of
// a server that is not there.
#pragma once
#include <xcb/xcb.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "present/present_error.h"

namespace ht::present {

class XConnection {
 public:
  // `display` as in $DISPLAY (":0", ":99"); "" uses $DISPLAY. Throws PresentError naming the display.
  explicit XConnection(const std::string& display);
  ~XConnection();
  XConnection(const XConnection&) = delete;
  XConnection& operator=(const XConnection&) = delete;

  xcb_connection_t* get() const { return connection_; }
  xcb_window_t root() const { return screen_->root; }
  xcb_screen_t* screen() const { return screen_; }
  const std::string& name() const { return name_; }
  // False once the server closed the connection (it went away); everything on it then fails.
  bool alive() const { return xcb_connection_has_error(connection_) == 0; }
  // The atom of `name`, created if needed. Throws PresentError.
  xcb_atom_t atom(const std::string& name) const;

 private:
  xcb_connection_t* connection_ = nullptr;
  xcb_screen_t* screen_ = nullptr;
  std::string name_;
};

// Frees an xcb reply at scope end.
struct FreeDeleter {
  void operator()(void* p) const { std::free(p); }
};
template <typename T>
using XReply = std::unique_ptr<T, FreeDeleter>;

}  // namespace ht::present
