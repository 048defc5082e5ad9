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

// Each panel that loaded becomes display "device:SERIAL" (a raw visual.json: lenticular, default placement);
// panels that did not load are logged with their DeviceError and left out.
void addDevices(const DeviceScan& scan, std::map<std::string, std::shared_ptr<const RegisteredDisplay>>& map,
                std::ostream& log) {
  if (!scan) return;
  const devices::Discovery found = scan();
  for (const std::string& note : found.notes) log << "holotraced: devices: " << note << "\n";
  for (const devices::FoundDevice& device : found.devices) {
    if (!device.loaded()) {
      log << "holotraced: panel skipped: " << device.problem() << "\n";
      continue;
    }
    const std::string id = "device:" + device.serial;
    try {
      RegisteredDisplay display{
          id,      parseDisplayConfig(device.calibration->json, device.location, {}), device.calibration->json,
          nullptr, std::string(devices::calibrationSourceName(device.source)),        device.serial};
      if (display.config.name.empty()) display.config.name = device.serial;
      map[id] = std::make_shared<const RegisteredDisplay>(std::move(display));
      const std::string type = device.deviceType.empty() ? "unknown type" : device.deviceType;
      log << "holotraced: panel " << device.serial << " (" << type << ") from "
          << devices::calibrationSourceName(device.source) << " " << device.location << " -> " << id << "\n";
    } catch (const Error& e) { log << "holotraced: panel skipped: " << e.what() << "\n"; }
  }
}

}  // namespace

DeviceScan deviceScanFor(const DeviceDiscoveryConfig& config) {
  if (!config.scan) return {};
  devices::DiscoveryOptions options;
  options.calibrationFile = config.calibrationFile;
  options.scanDrives = config.drives;
  options.scanUsb = config.usb;
  options.usb.detachKernelDriver = config.detachKernelDriver;
  if (!config.mountinfo.empty()) options.drives.mountinfo = config.mountinfo;
  if (!config.byLabelDir.empty()) options.drives.byLabelDir = config.byLabelDir;
  return [options] { return devices::discoverDevices(options); };
}

DisplayRegistry::DisplayRegistry(std::filesystem::path displaysDir, DeviceScan scanDevices)
    : dir_(std::move(displaysDir)), scanDevices_(std::move(scanDevices)) {}

std::size_t DisplayRegistry::reload(std::ostream& log) {
  auto map = std::make_shared<Map>();
  addBuiltins(*map, log);
  std::error_code ec;
  if (!dir_.empty() && std::filesystem::is_directory(dir_, ec)) {
    for (const auto& entry : std::filesystem::directory_iterator(dir_, ec)) {
      if (entry.path().extension() != ".json" || !entry.is_regular_file()) continue;
      try {
        const std::string id = entry.path().stem().string();
        if (id.rfind("builtin:", 0) == 0) {  // "builtin:portrait.json" must not replace the builtin
          log << "holotraced: display config skipped: " << entry.path().string()
              << ": ids starting with 'builtin:' are reserved for the builtin displays (rename the file)\n";
          continue;
        }
        RegisteredDisplay display{id, loadDisplayConfig(entry.path()), readText(entry.path()), nullptr, "displays-dir",
                                  ""};
        if (display.config.model == DisplayModel::RayTable) {
          display.rayTable = std::make_shared<const RayTable>(frame_io::loadDisplayRayTable(display.config));
        }
        (*map)[id] = std::make_shared<const RegisteredDisplay>(std::move(display));
      } catch (const Error& e) { log << "holotraced: display config skipped: " << e.what() << "\n"; }
    }
  }
  addDevices(scanDevices_, *map, log);
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
