// display_registry.cpp - see display_registry.h.
#include "server/display_registry.h"

#include <fstream>
#include <sstream>

#include "camera_models/embedded_display_configs.h"
#include "common/error.h"
#include "frame_io/ray_table_exr.h"

namespace ht::server {
namespace {

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void addBuiltins(std::map<std::string, std::shared_ptr<const RegisteredDisplay>>& map, std::ostream& log) {
  for (const auto& embedded : detail::embeddedDisplayConfigs()) {
    const std::string id = "builtin:" + std::string(embedded.name);
    try {
      map[id] = std::make_shared<const RegisteredDisplay>(
          RegisteredDisplay{id, builtinDisplay(embedded.name), std::string(embedded.json), nullptr});
    } catch (const Error& e) { log << "holotraced: builtin display skipped: " << e.what() << "\n"; }
  }
}

}  // namespace

DisplayRegistry::DisplayRegistry(std::filesystem::path displaysDir) : dir_(std::move(displaysDir)) {}

std::size_t DisplayRegistry::reload(std::ostream& log) {
  auto map = std::make_shared<Map>();
  addBuiltins(*map, log);
  std::error_code ec;
  if (!dir_.empty() && std::filesystem::is_directory(dir_, ec)) {
    for (const auto& entry : std::filesystem::directory_iterator(dir_, ec)) {
      if (entry.path().extension() != ".json" || !entry.is_regular_file()) continue;
      try {
        const std::string id = entry.path().stem().string();
        RegisteredDisplay display{id, loadDisplayConfig(entry.path()), readText(entry.path()), nullptr};
        if (display.config.model == DisplayModel::RayTable) {
          display.rayTable = std::make_shared<const RayTable>(frame_io::loadDisplayRayTable(display.config));
        }
        (*map)[id] = std::make_shared<const RegisteredDisplay>(std::move(display));
      } catch (const Error& e) { log << "holotraced: display config skipped: " << e.what() << "\n"; }
    }
  }
  const std::size_t count = map->size();
  std::lock_guard lock(mutex_);
  displays_ = std::move(map);
  return count;
}

std::vector<std::shared_ptr<const RegisteredDisplay>> DisplayRegistry::list() const {
  std::shared_ptr<const Map> map;
  {
    std::lock_guard lock(mutex_);
    map = displays_;
  }
  std::vector<std::shared_ptr<const RegisteredDisplay>> out;
  if (map) {
    for (const auto& [id, display] : *map) out.push_back(display);
  }
  return out;
}

std::shared_ptr<const RegisteredDisplay> DisplayRegistry::find(const std::string& id) const {
  std::lock_guard lock(mutex_);
  if (displays_) {
    auto it = displays_->find(id);
    if (it != displays_->end()) return it->second;
  }
  throw UnknownDisplay("unknown display id '" + id + "' (ListDisplays names them)");
}

}  // namespace ht::server
