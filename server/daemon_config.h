// daemon_config.h - holotraced's configuration file (JSON, docs/SERVICE.md "Configuration"). Every limit has a
// default and is enforced before anything is allocated (docs/SERVICE.md §6 "Limits at the API edge").
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ht::server {

struct Limits {
  std::uint32_t maxClients = 16;                 // concurrent streaming calls (RenderFrame/StreamFrames/Capture)
  std::uint32_t maxMessageBytes = 4u << 20;      // gRPC receive limit per message
  std::uint64_t maxSceneBytes = 256ull << 20;    // LoadScene file size / UploadScene total
  std::uint64_t maxTriangles = 5'000'000;        // per scene
  std::uint32_t maxPanelPixels = 8192u * 8192u;  // width * height of a display frame
  std::uint32_t maxFramesInFlight = 2;           // queued + rendering frames per client (peer)
  std::uint32_t maxCaptureFrames = 1000;
  std::uint32_t maxSpp = 256;
  double maxFramesPerSecond = 120.0;
};

struct DaemonConfig {
  std::filesystem::path displaysDir;  // *.json display configs, ids = file names; empty = builtins only
  std::filesystem::path sceneRoot;    // LoadScene paths resolve beneath it
  std::filesystem::path outputRoot;   // Capture writes beneath it
  std::filesystem::path workDir;      // private temp files of uploaded scenes (created 0700)
  std::vector<std::string> listen;    // gRPC addresses: "unix:/path" or "127.0.0.1:PORT"
  int deviceIndex = -1;               // Vulkan device, -1 = automatic
  Limits limits;
  std::string sourcePath;  // file the config came from (for errors)
};

// The default socket: $XDG_RUNTIME_DIR/holotrace/holotraced.sock, else /run/holotrace/holotraced.sock.
std::string defaultListenAddress();

// Parses the config file. Relative paths resolve against the file's directory. Throws ConfigError.
DaemonConfig loadDaemonConfig(const std::filesystem::path& file);
DaemonConfig parseDaemonConfig(const std::string& json, const std::string& sourceName,
                               const std::filesystem::path& baseDir);

}  // namespace ht::server
