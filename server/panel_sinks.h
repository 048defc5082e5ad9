// panel_sinks.h - the daemon's display sinks: one present::PanelSink per display named by the config's "present"
// section, each with its own present thread, window and swapchain (docs/SERVICE.md §11, docs/DISPLAY.md). A sink whose
// panel or X server is missing logs and keeps retrying; files and gRPC clients are served meanwhile.
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
  // Starts one sink per configured display. Throws ConfigError for an unknown display id or a display whose frame is
  // not one image (several views cannot be shown 1:1 on one panel).
  // `source` names the daemon config file in errors.
  PanelSinks(const PresentConfig& config, const DisplayRegistry& displays, int vulkanDevice, const std::string& source,
             std::ostream& log);
  ~PanelSinks();

  // The sink of `displayId`, or nullptr if that display has none.
  present::PanelSink* find(const std::string& displayId) const;
  // (display id, stats) of every sink, in id order.
  std::vector<std::pair<std::string, present::PanelSinkStats>> stats() const;
  const std::string& xDisplay() const { return xDisplay_; }
  std::size_t size() const { return sinks_.size(); }

 private:
  std::string xDisplay_;
  std::mutex logMutex_;
  std::map<std::string, std::unique_ptr<present::PanelSink>> sinks_;
};

}  // namespace ht::server
