// daemon_config.cpp - see daemon_config.h.
#include "server/daemon_config.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/error.h"
#include "common/json_nesting.h"

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

// An integer limit in [lo, hi]. JSON numbers with a fraction or an exponent (0.5, 1e20) are not integers: they are
// refused, never truncated or wrapped into the field's type.
template <typename T>
void readInteger(const json& limits, const char* key, T& value, std::uint64_t lo, std::uint64_t hi,
                 const std::string& source) {
  if (!limits.contains(key)) return;
  const json& v = limits[key];
  const std::string expected = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  const std::string field = std::string("limits.") + key;
  if (!v.is_number_integer()) throw ConfigError(source, field, v.dump(), expected);
  const bool negative = !v.is_number_unsigned() && v.get<std::int64_t>() < 0;
  if (negative || v.get<std::uint64_t>() < lo || v.get<std::uint64_t>() > hi) {
    throw ConfigError(source, field, v.dump(), expected);
  }
  value = static_cast<T>(v.get<std::uint64_t>());
}

void readReal(const json& limits, const char* key, double& value, double lo, double hi, const std::string& source) {
  if (!limits.contains(key)) return;
  const json& v = limits[key];
  if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi)) {
    throw ConfigError(source, std::string("limits.") + key, v.dump(),
                      "a number in [" + json(lo).dump() + ", " + json(hi).dump() + "]");
  }
  value = v.get<double>();
}

Limits parseLimits(const json& doc, const std::string& source) {
  Limits l;
  if (!doc.contains("limits")) return l;
  const json& j = doc["limits"];
  if (!j.is_object()) throw ConfigError(source, "limits", j.dump(), "an object");
  constexpr std::uint64_t kU32 = 0xffffffffull;
  readInteger(j, "max_clients", l.maxClients, 1, 4096, source);
  readInteger(j, "max_message_bytes", l.maxMessageBytes, 1024, 0x7fffffffull, source);  // gRPC takes an int
  readInteger(j, "max_scene_bytes", l.maxSceneBytes, 1, 1ull << 40, source);
  readInteger(j, "max_triangles", l.maxTriangles, 1, kU32, source);
  readInteger(j, "max_panel_pixels", l.maxPanelPixels, 1, kU32, source);
  readInteger(j, "max_frames_in_flight", l.maxFramesInFlight, 1, 64, source);
  readInteger(j, "max_capture_frames", l.maxCaptureFrames, 1, 1'000'000, source);
  readInteger(j, "max_spp", l.maxSpp, 1, 65536, source);
  readReal(j, "max_frames_per_second", l.maxFramesPerSecond, kMinFramesPerSecond, 1000.0, source);
  readInteger(j, "max_scene_sessions", l.maxSceneSessions, 1, 65536, source);
  readReal(j, "scene_idle_seconds", l.sceneIdleSeconds, 0.05, 7 * 86400.0, source);
  readInteger(j, "max_scene_memory_bytes", l.maxSceneMemoryBytes, 1ull << 20, 1ull << 44, source);
  readInteger(j, "max_uploads", l.maxUploads, 1, 1024, source);
  readInteger(j, "max_upload_bytes_in_flight", l.maxUploadBytesInFlight, 1, 1ull << 44, source);
  readReal(j, "upload_idle_seconds", l.uploadIdleSeconds, 0.05, 86400.0, source);
  readReal(j, "stream_stall_seconds", l.streamStallSeconds, 0.05, 86400.0, source);
  readInteger(j, "max_accumulator_bytes", l.maxAccumulatorBytes, 0, 1ull << 44, source);
  readReal(j, "stream_target_error", l.streamTargetError, 0.0, 1000.0, source);
  readInteger(j, "stream_max_spp", l.streamMaxSpp, 1, 1u << 20, source);
  if (l.maxUploadBytesInFlight < l.maxSceneBytes) {  // else the largest allowed upload could never run
    throw ConfigError(source, "limits.max_upload_bytes_in_flight", std::to_string(l.maxUploadBytesInFlight),
                      "at least limits.max_scene_bytes = " + std::to_string(l.maxSceneBytes));
  }
  return l;
}

int parseDevice(const json& doc, const std::string& source) {
  if (!doc.contains("device")) return -1;
  const json& d = doc["device"];
  if (!d.is_number_integer() || d.get<std::int64_t>() < -1 || d.get<std::int64_t>() > 1024) {
    throw ConfigError(source, "device", d.dump(), "a Vulkan device index >= 0, or -1 for automatic");
  }
  return d.get<int>();
}

bool readFlag(const json& object, const char* key, bool fallback, const std::string& source) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_boolean()) {
    throw ConfigError(source, std::string("devices.") + key, object[key].dump(), "true or false");
  }
  return object[key].get<bool>();
}

DeviceDiscoveryConfig parseDevices(const json& doc, const std::filesystem::path& baseDir, const std::string& source) {
  DeviceDiscoveryConfig d;
  if (!doc.contains("devices")) return d;
  const json& j = doc["devices"];
  if (!j.is_object()) throw ConfigError(source, "devices", j.dump(), "an object (docs/DISPLAY.md)");
  for (const auto& [key, value] : j.items()) {
    static const char* const kKeys[] = {"scan",      "calibration_file", "drives", "usb", "detach_kernel_driver",
                                        "mountinfo", "by_label_dir"};
    if (std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys)) {
      throw ConfigError(
          source, "devices." + key, value.dump(),
          "a known key: scan, calibration_file, drives, usb, detach_kernel_driver, mountinfo, by_label_dir");
    }
  }
  d.scan = readFlag(j, "scan", d.scan, source);
  d.drives = readFlag(j, "drives", d.drives, source);
  d.usb = readFlag(j, "usb", d.usb, source);
  d.detachKernelDriver = readFlag(j, "detach_kernel_driver", d.detachKernelDriver, source);
  d.calibrationFile = resolvePath(j, "calibration_file", baseDir, source);
  d.mountinfo = resolvePath(j, "mountinfo", baseDir, source);
  d.byLabelDir = resolvePath(j, "by_label_dir", baseDir, source);
  return d;
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
  if (const auto deep = findJsonNestingViolation(text))
    throw ConfigError(source, "(document)", "", jsonNestingMessage(*deep));
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
  c.deviceIndex = parseDevice(doc, source);
  c.limits = parseLimits(doc, source);
  c.devices = parseDevices(doc, baseDir, source);
  c.present = parsePresentConfig(doc, source);
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
