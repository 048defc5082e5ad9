// panel_sinks.h - the daemon's display sinks: one present::PanelSink per display named by the config's "present"
// section, each with its own present thread, window and swapchain (docs/SERVICE.md §11, docs/DISPLAY.md). A sink whose
// panel or X server is missing logs and keeps retrying; files and gRPC clients are served meanwhile. update() (SIGHUP,
// after the displays were re-read) adds sinks for displays that appeared and removes those of displays that are gone;
// a sink whose display is unchanged keeps running untouched.
#pragma once
#include <map>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "present/panel_sink.h"
#include "server/display_registry.h"
#include "server/present_config.h"

namespace ht::server {

class PanelSinks {
 public:
  // Starts one sink per configured display. Throws ConfigError for an unknown display id (except "device:..." ids,
  // which wait for their panel to be plugged in) or a display whose frame is not one image (several views cannot be
  // shown 1:1 on one panel). `source` names the daemon config file in errors.
  PanelSinks(PresentConfig config, const DisplayRegistry& displays, int vulkanDevice, std::string source,
             std::ostream& log);
  ~PanelSinks();

  // Re-evaluates the configured displays against `displays` (just reloaded): adds sinks for displays that appeared,
  // removes those whose display is gone or can no longer be shown, replaces a sink whose monitor request changed
  // (a display config's size or "panel" section); every other sink is left alone. Logs each change, never throws.
  void update(const DisplayRegistry& displays);

  // The sink of `displayId`, or nullptr if that display has none. Shared: a removed sink lives until its last user.
  std::shared_ptr<present::PanelSink> find(const std::string& displayId) const;
  // (display id, stats) of every sink, in id order.
  std::vector<std::pair<std::string, present::PanelSinkStats>> stats() const;
  const std::string& xDisplay() const { return config_.xDisplay; }
  std::size_t size() const;

 private:
  struct Entry {
    present::PanelRequest request;
    std::shared_ptr<present::PanelSink> sink;
  };
  std::map<std::string, present::PanelRequest> wanted(const DisplayRegistry& displays, bool atStart);
  std::shared_ptr<present::PanelSink> startSink(const std::string& displayId, const present::PanelRequest& request);
  void logLine(const std::string& line);

  PresentConfig config_;
  present::FrameTransferChoice transfer_;  // HOLOTRACE_PANEL_TRANSFER, read once at start
  int vulkanDevice_;
  std::string source_;
  std::ostream& log_;
  std::mutex logMutex_;
  mutable std::mutex mutex_;  // guards sinks_ (update() runs on the signal thread, find()/stats() on RPC threads)
  std::map<std::string, Entry> sinks_;
};

}  // namespace ht::server
