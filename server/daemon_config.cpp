// daemon_config.cpp - see daemon_config.h.
#include "server/daemon_config.h"

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/error.h"

namespace ht::server {
namespace {

using nlohmann::json;

std::filesystem::path resolvePath(const json& doc, const char* key, const std::filesystem::path& baseDir,
                                  const std::string& source) {
  if (!doc.contains(key)) return {};
  if (!doc[key].is_string()) throw ConfigError(source, key, doc[key].dump(), "a path string");
  const std::filesystem::path p = doc[key].get<std::string>();
  return p.is_absolute() ? p : baseDir / p;
}

template <typename T>
void readLimit(const json& limits, const char* key, T& value, const std::string& source) {
  if (!limits.contains(key)) return;
  const json& v = limits[key];
  if (!v.is_number() || v.get<double>() <= 0)
    throw ConfigError(source, std::string("limits.") + key, v.dump(), "a positive number");
  value = v.get<T>();
}

Limits parseLimits(const json& doc, const std::string& source) {
  Limits l;
  if (!doc.contains("limits")) return l;
  const json& j = doc["limits"];
  if (!j.is_object()) throw ConfigError(source, "limits", j.dump(), "an object");
  readLimit(j, "max_clients", l.maxClients, source);
  readLimit(j, "max_message_bytes", l.maxMessageBytes, source);
  readLimit(j, "max_scene_bytes", l.maxSceneBytes, source);
  readLimit(j, "max_triangles", l.maxTriangles, source);
  readLimit(j, "max_panel_pixels", l.maxPanelPixels, source);
  readLimit(j, "max_frames_in_flight", l.maxFramesInFlight, source);
  readLimit(j, "max_capture_frames", l.maxCaptureFrames, source);
  readLimit(j, "max_spp", l.maxSpp, source);
  readLimit(j, "max_frames_per_second", l.maxFramesPerSecond, source);
  return l;
}

}  // namespace

std::string defaultListenAddress() {
  const char* runtime = std::getenv("XDG_RUNTIME_DIR");
  const std::filesystem::path dir =
      runtime && *runtime ? std::filesystem::path(runtime) / "holotrace" : std::filesystem::path("/run/holotrace");
  return "unix:" + (dir / "holotraced.sock").string();
}

DaemonConfig parseDaemonConfig(const std::string& text, const std::string& source,
                               const std::filesystem::path& baseDir) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    throw ConfigError(source, "(document)", "", std::string("valid JSON: ") + e.what());
  }
  if (!doc.is_object()) throw ConfigError(source, "(document)", doc.dump(), "a JSON object");
  DaemonConfig c;
  c.sourcePath = source;
  c.displaysDir = resolvePath(doc, "displays_dir", baseDir, source);
  c.sceneRoot = resolvePath(doc, "scene_root", baseDir, source);
  c.outputRoot = resolvePath(doc, "output_root", baseDir, source);
  c.workDir = resolvePath(doc, "work_dir", baseDir, source);
  if (c.sceneRoot.empty()) throw ConfigError(source, "scene_root", "(missing)", "a directory path");
  if (c.outputRoot.empty()) throw ConfigError(source, "output_root", "(missing)", "a directory path");
  if (doc.contains("listen")) {
    const json& l = doc["listen"];
    if (!l.is_array()) throw ConfigError(source, "listen", l.dump(), "an array of addresses");
    for (const json& a : l) {
      if (!a.is_string()) throw ConfigError(source, "listen", a.dump(), "an address string");
      c.listen.push_back(a.get<std::string>());
    }
  }
  if (c.listen.empty()) c.listen.push_back(defaultListenAddress());
  if (doc.contains("device")) c.deviceIndex = doc["device"].get<int>();
  c.limits = parseLimits(doc, source);
  return c;
}

DaemonConfig loadDaemonConfig(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw ConfigError(file.string(), "(file)", "", "a readable JSON file");
  std::stringstream text;
  text << in.rdbuf();
  return parseDaemonConfig(text.str(), file.string(), file.parent_path());
}

}  // namespace ht::server
