// xvfb_server.h - a private Xvfb for the display-sink tests and the present benchmark (not used by the sink itself):
// started on a free display number
// (-displayfd), with -noreset so RandR monitors survive the last client, ended by PID. Monitors and EDIDs are set
// through RandR requests, as `xrandr --setmonitor` and a synthetic EDID property would (docs/DISPLAY.md).
#pragma once
#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "present/randr_snapshot.h"
#include "present/x_connection.h"

namespace ht::present {

class XvfbServer {
 public:
  // Starts `Xvfb -screen 0 WxHx24 -noreset -nolisten tcp -displayfd N`; throws PresentError if it does not come up.
  // `display` "" picks a free number; ":N" restarts a server on a number a previous one had (hot-plug tests).
  XvfbServer(std::uint32_t width, std::uint32_t height, const std::string& display = "");
  ~XvfbServer();  // SIGTERM to the PID, then waits for it
  XvfbServer(const XvfbServer&) = delete;
  XvfbServer& operator=(const XvfbServer&) = delete;

  const std::string& display() const { return display_; }  // ":N"
  pid_t pid() const { return pid_; }
  const XConnection& connection() const { return *x_; }

  // RandR 1.5 monitor `name` at `rect` showing `outputs` (names), like `xrandr --setmonitor`.
  void setMonitor(const std::string& name, const Rect& rect, const std::vector<std::string>& outputs);
  void deleteMonitor(const std::string& name);
  // Sets the EDID property of output `output` (Xvfb has one, "screen").
  void setEdid(const std::string& output, const std::vector<std::uint8_t>& edid);
  // Ends the server now (the tests of a vanishing X server).
  void kill();

 private:
  std::uint32_t outputId(const std::string& name) const;
  void runXrandr(const std::vector<std::string>& args) const;
  pid_t pid_ = -1;
  std::string display_;
  std::unique_ptr<XConnection> x_;
};

}  // namespace ht::present
