// panel_sinks.cpp - config "present" -> sinks (panel size from the display's frame shape).
#include "server/panel_sinks.h"

#include "common/error.h"
#include "server/frame_job.h"

namespace ht::server {
namespace {

// "auto": the lenticular displays of the displays directory (the builtins are examples, not the user's panels).
std::vector<PanelTarget> autoTargets(const DisplayRegistry& displays) {
  std::vector<PanelTarget> targets;
  for (const auto& d : displays.list()) {
    if (d->config.model == DisplayModel::Lenticular && !d->id.starts_with("builtin:")) {
      targets.push_back(PanelTarget{d->id, std::nullopt, std::nullopt});
    }
  }
  return targets;
}

// The daemon config's output/geometry of the entry, else the display config's "panel" section (docs/SERVICE.md §11).
present::PanelRequest panelRequest(const PanelTarget& target, const RegisteredDisplay& display,
                                   const std::string& source) {
  const gpu::FrameShape shape = displayFrameShape(display);
  if (shape.views != 1) {
    throw ConfigError(
        source, "present", target.displayId,
        "a display whose frame is one image (this one renders " + std::to_string(shape.views) + " views)");
  }
  present::PanelRequest request{shape.width, shape.height, target.output, std::nullopt};
  if (target.geometry) request.geometry = present::parseGeometry(*target.geometry);
  if (!target.output && !target.geometry) request = present::withPlacement(request, display.config.panel);
  return request;
}

}  // namespace

PanelSinks::PanelSinks(const PresentConfig& config, const DisplayRegistry& displays, int vulkanDevice,
                       const std::string& source, std::ostream& log)
    : xDisplay_(config.xDisplay) {
  std::vector<PanelTarget> targets = config.mode == PresentConfig::Mode::Auto ? autoTargets(displays) : config.panels;
  if (config.mode == PresentConfig::Mode::None) targets.clear();
  for (const PanelTarget& target : targets) {
    std::shared_ptr<const RegisteredDisplay> display;
    try {
      display = displays.find(target.displayId);
    } catch (const Error& e) {
      throw ConfigError(source, "present", target.displayId, std::string("a known display id: ") + e.what());
    }
    present::PanelSinkOptions options;
    options.xDisplay = config.xDisplay;
    options.panel = panelRequest(target, *display, source);
    options.vulkanDevice = vulkanDevice;
    options.log = [this, &log, id = target.displayId](const std::string& line) {
      std::lock_guard lock(logMutex_);
      log << "holotraced: panel " << id << ": " << line << "\n" << std::flush;
    };
    sinks_[target.displayId] = std::make_unique<present::PanelSink>(std::move(options));
  }
}

PanelSinks::~PanelSinks() = default;

present::PanelSink* PanelSinks::find(const std::string& displayId) const {
  auto it = sinks_.find(displayId);
  return it == sinks_.end() ? nullptr : it->second.get();
}

std::vector<std::pair<std::string, present::PanelSinkStats>> PanelSinks::stats() const {
  std::vector<std::pair<std::string, present::PanelSinkStats>> out;
  for (const auto& [id, sink] : sinks_) out.emplace_back(id, sink->stats());
  return out;
}

}  // namespace ht::server
