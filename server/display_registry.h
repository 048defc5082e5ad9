// display_registry.h - the displays a client may name: the builtins ("builtin:NAME") and every *.json in the
// daemon's displays directory (id = file stem). reload() (SIGHUP) re-reads the directory; readers never block on it
// for long and always see a complete set.
#pragma once
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "camera_models/display_config.h"
#include "camera_models/ray_table.h"
#include "server/errors.h"

namespace ht::server {

struct RegisteredDisplay {
  std::string id;
  DisplayConfig config;
  std::string sourceText;                    // the config file (or embedded config) verbatim
  std::shared_ptr<const RayTable> rayTable;  // model "ray-table": its table, read when the display is registered
};

class DisplayRegistry {
 public:
  explicit DisplayRegistry(std::filesystem::path displaysDir);

  // Re-reads the directory; a file that fails to parse is reported on `log` and left out. Returns the count.
  std::size_t reload(std::ostream& log);
  std::vector<std::shared_ptr<const RegisteredDisplay>> list() const;
  std::shared_ptr<const RegisteredDisplay> find(const std::string& id) const;  // throws UnknownDisplay

 private:
  using Map = std::map<std::string, std::shared_ptr<const RegisteredDisplay>>;
  std::filesystem::path dir_;
  mutable std::mutex mutex_;
  std::shared_ptr<const Map> displays_;
};

}  // namespace ht::server
