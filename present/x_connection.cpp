// x_connection.cpp - connect, find the default screen, intern atoms.
#include "present/x_connection.h"

#include <cstdlib>

namespace ht::present {

XConnection::XConnection(const std::string& display) {
  const char* env = std::getenv("DISPLAY");
  name_ = !display.empty() ? display : (env ? env : "");
  if (name_.empty()) throw PresentError("no X display given and $DISPLAY is not set (use --display :0)");
  int screenNumber = 0;
  connection_ = xcb_connect(name_.c_str(), &screenNumber);
  if (xcb_connection_has_error(connection_)) {
    xcb_disconnect(connection_);
    connection_ = nullptr;
    throw PresentError("cannot connect to X display '" + name_ +
                       "' (is the X server running, and may this user use it?)");
  }
  xcb_screen_iterator_t it = xcb_setup_roots_iterator(xcb_get_setup(connection_));
  for (int i = 0; i < screenNumber && it.rem; ++i) xcb_screen_next(&it);
  if (!it.rem) {
    xcb_disconnect(connection_);
    connection_ = nullptr;
    throw PresentError("X display '" + name_ + "' has no screen " + std::to_string(screenNumber));
  }
  screen_ = it.data;
}

XConnection::~XConnection() {
  if (connection_) xcb_disconnect(connection_);
}

xcb_atom_t XConnection::atom(const std::string& name) const {
  auto cookie = xcb_intern_atom(connection_, 0, static_cast<std::uint16_t>(name.size()), name.c_str());
  XReply<xcb_intern_atom_reply_t> reply(xcb_intern_atom_reply(connection_, cookie, nullptr));
  if (!reply) throw PresentError("X display '" + name_ + "': cannot intern atom " + name);
  return reply->atom;
}

}  // namespace ht::present
