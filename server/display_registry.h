// display_registry.h - the displays a client may name: the builtins ("builtin:NAME"), every *.json in the
// daemon's displays directory (id = file stem) and the Looking Glass panels found on the host ("device:SERIAL",
// devices/device_discovery.h). reload() (SIGHUP) re-reads the directory and rescans the panels; readers never block
// on it for long and always see a complete set.
#pragma once
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "camera_models/display_config.h"
#include "camera_models/ray_table.h"
#include "devices/device_discovery.h"
#include "server/daemon_config.h"
#include "server/errors.h"

namespace ht::server {

struct RegisteredDisplay {
  std::string id;
  DisplayConfig config;
  std::string sourceText;                    // the config file (or embedded config) verbatim
  std::shared_ptr<const RayTable> rayTable;  // model "ray-table": its table, read when the display is registered
  // Where the display came from (ListDisplays `source`): "builtin", "displays-dir", or a device calibration source
  // ("config-file", "mounted-drive", "usb-hid"; devices::calibrationSourceName).
  std::string source = "builtin";
  std::string serial;  // device displays: the panel's serial
};

// Scans the host for panels (devices::discoverDevices with the daemon's options; tests inject their own).
using DeviceScan = std::function<devices::Discovery()>;
DeviceScan deviceScanFor(const DeviceDiscoveryConfig& config);  // empty function when config.scan is false

class DisplayRegistry {
 public:
  explicit DisplayRegistry(std::filesystem::path displaysDir, DeviceScan scanDevices = {});

  // Re-reads the directory; a file that fails to parse is reported on `log` and left out. Returns the count.
  std::size_t reload(std::ostream& log);
  std::vector<std::shared_ptr<const RegisteredDisplay>> list() const;
  std::shared_ptr<const RegisteredDisplay> find(const std::string& id) const;  // throws UnknownDisplay

 private:
  using Map = std::map<std::string, std::shared_ptr<const RegisteredDisplay>>;
  std::filesystem::path dir_;
  DeviceScan scanDevices_;
  mutable std::mutex mutex_;
  std::shared_ptr<const Map> displays_;
};

}  // namespace ht::server
