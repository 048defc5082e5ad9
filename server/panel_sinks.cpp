// panel_sinks.cpp - config "present" -> sinks (panel size from the display's frame shape), re-evaluated on SIGHUP.
#include "server/panel_sinks.h"

#include "common/error.h"
#include "server/frame_job.h"

namespace ht::server {
namespace {

constexpr const char* kDevicePrefix = "device:";

// "auto": the lenticular displays of the displays directory and the panels found on the host (the builtins are
// examples, not the user's panels).
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

bool sameRequest(const present::PanelRequest& a, const present::PanelRequest& b) {
  return a.screenWidth == b.screenWidth && a.screenHeight == b.screenHeight && a.output == b.output &&
         a.geometry == b.geometry;
}

}  // namespace

PanelSinks::PanelSinks(PresentConfig config, const DisplayRegistry& displays, int vulkanDevice, std::string source,
                       std::ostream& log)
    : config_(std::move(config)),
      transfer_(present::frameTransferFromEnvironment()),
      vulkanDevice_(vulkanDevice),
      source_(std::move(source)),
      log_(log) {
  for (const auto& [id, request] : wanted(displays, true)) sinks_[id] = Entry{request, startSink(id, request)};
}

PanelSinks::~PanelSinks() = default;

void PanelSinks::logLine(const std::string& line) {
  std::lock_guard lock(logMutex_);
  log_ << "holotraced: " << line << "\n" << std::flush;
}

// Display id -> monitor request of every display that should have a sink now. At start a bad entry throws
// ConfigError; later (SIGHUP) it is logged and left out, and the daemon keeps running.
std::map<std::string, present::PanelRequest> PanelSinks::wanted(const DisplayRegistry& displays, bool atStart) {
  std::vector<PanelTarget> targets = config_.mode == PresentConfig::Mode::Auto ? autoTargets(displays) : config_.panels;
  if (config_.mode == PresentConfig::Mode::None) targets.clear();
  std::map<std::string, present::PanelRequest> out;
  for (const PanelTarget& target : targets) {
    try {
      std::shared_ptr<const RegisteredDisplay> display;
      try {
        display = displays.find(target.displayId);
      } catch (const Error& e) {
        if (target.displayId.starts_with(kDevicePrefix)) {
          logLine("panel " + target.displayId + ": not plugged in (a sink starts when SIGHUP finds it)");
          continue;
        }
        throw ConfigError(source_, "present", target.displayId, std::string("a known display id: ") + e.what());
      }
      out[target.displayId] = panelRequest(target, *display, source_);
    } catch (const Error& e) {
      if (atStart) throw;
      logLine("panel " + target.displayId + ": no sink: " + e.what());
    }
  }
  return out;
}

std::shared_ptr<present::PanelSink> PanelSinks::startSink(const std::string& displayId,
                                                          const present::PanelRequest& request) {
  present::PanelSinkOptions options;
  options.xDisplay = config_.xDisplay;
  options.panel = request;
  options.vulkanDevice = vulkanDevice_;
  options.transfer = transfer_;
  options.log = [this, displayId](const std::string& line) { logLine("panel " + displayId + ": " + line); };
  return std::make_shared<present::PanelSink>(std::move(options));
}

void PanelSinks::update(const DisplayRegistry& displays) {
  const std::map<std::string, present::PanelRequest> now = wanted(displays, false);
  std::vector<std::shared_ptr<present::PanelSink>> retired;  // stopped after the lock is released
  std::lock_guard lock(mutex_);
  for (auto it = sinks_.begin(); it != sinks_.end();) {
    auto keep = now.find(it->first);
    if (keep != now.end() && sameRequest(keep->second, it->second.request)) {
      ++it;
      continue;
    }
    logLine("panel " + it->first + ": sink removed (" +
            (keep == now.end() ? std::string("display gone") : std::string("its monitor request changed")) + ")");
    retired.push_back(std::move(it->second.sink));
    it = sinks_.erase(it);
  }
  for (const auto& [id, request] : now) {
    if (sinks_.count(id)) continue;
    sinks_[id] = Entry{request, startSink(id, request)};
    logLine("panel " + id + ": sink added");
  }
}

std::shared_ptr<present::PanelSink> PanelSinks::find(const std::string& displayId) const {
  std::lock_guard lock(mutex_);
  auto it = sinks_.find(displayId);
  return it == sinks_.end() ? nullptr : it->second.sink;
}

std::vector<std::pair<std::string, present::PanelSinkStats>> PanelSinks::stats() const {
  std::vector<std::pair<std::string, std::shared_ptr<present::PanelSink>>> sinks;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [id, entry] : sinks_) sinks.emplace_back(id, entry.sink);
  }
  std::vector<std::pair<std::string, present::PanelSinkStats>> out;
  for (const auto& [id, sink] : sinks) out.emplace_back(id, sink->stats());
  return out;
}

std::size_t PanelSinks::size() const {
  std::lock_guard lock(mutex_);
  return sinks_.size();
}

}  // namespace ht::server
