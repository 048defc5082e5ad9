// daemon_config.h - holotraced's configuration file (JSON, docs/SERVICE.md "Configuration"). Every limit has a
// default and is enforced before anything is allocated (docs/SERVICE.md §6 "Limits at the API edge").
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "server/present_config.h"

namespace ht::server {

// StreamFrames' lowest frame rate (one frame per 1000 s): below it 1/fps is refused, not computed (docs/SERVICE.md §2).
inline constexpr double kMinFramesPerSecond = 0.001;

// Ranges of every limit: docs/SERVICE.md §2; values outside them, or fractional counts, are a ConfigError.
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
  // Scene sessions and contents (server/scene_library.h, docs/SERVICE.md §5 "Scene sessions and memory").
  std::uint32_t maxSceneSessions = 256;            // open sessions; the least recently used idle one makes room
  double sceneIdleSeconds = 600.0;                 // a session unused this long ends
  std::uint64_t maxSceneMemoryBytes = 2ull << 30;  // estimated Scene + BVH + device buffers of all contents
  // Stalled clients (server/call_watchdog.h, server/upload_budget.h, docs/SERVICE.md §5 "Stalled clients").
  std::uint32_t maxUploads = 4;                         // UploadScene calls at once
  std::uint64_t maxUploadBytesInFlight = 512ull << 20;  // declared bytes of the uploads in flight, >= max_scene_bytes
  double uploadIdleSeconds = 30.0;                      // an upload waiting this long for its next chunk is cancelled
  double streamStallSeconds = 30.0;                     // a Write held back this long (client not reading): cancelled
  // Progressive StreamFrames (server/progressive_streams.h, docs/SERVICE.md §4.1).
  std::uint64_t maxAccumulatorBytes =
      1ull << 30;                    // device sums + segment masks of all progressive streams (64 B per target)
  double streamTargetError = 0.02;   // default stop rule: per-target error estimate below this ...
  std::uint32_t streamMaxSpp = 256;  // ... or this many accumulated samples per target
};

// Looking Glass panels found on this host become displays "device:SERIAL" (config key "devices"; docs/DISPLAY.md
// "Calibration from the device"). Scanned at start and on SIGHUP.
struct DeviceDiscoveryConfig {
  bool scan = true;                             // "scan": false = no device displays
  std::filesystem::path calibrationFile;        // "calibration_file": an explicit visual.json, trusted first
  bool drives = true;                           // "drives": LKG_calibration/visual.json on mounted volumes
  bool usb = true;                              // "usb": Gen1 panels over USB HID
  bool detachKernelDriver = true;               // "detach_kernel_driver"
  std::filesystem::path mountinfo, byLabelDir;  // "mountinfo", "by_label_dir": replace the system roots (tests)
};

struct DaemonConfig {
  std::filesystem::path displaysDir;  // *.json display configs, ids = file names; empty = builtins only
  std::filesystem::path sceneRoot;    // LoadScene paths resolve beneath it
  std::filesystem::path outputRoot;   // Capture writes beneath it
  std::filesystem::path workDir;      // private temp files of uploaded scenes (created 0700)
  std::vector<std::string> listen;    // gRPC addresses: "unix:/path" or "127.0.0.1:PORT"
  int deviceIndex = -1;               // Vulkan device, -1 = automatic
  Limits limits;
  DeviceDiscoveryConfig devices;
  PresentConfig present;   // "present" / "x_display": panel sinks (server/present_config.h)
  std::string sourcePath;  // file the config came from (for errors)
};

// The default socket: $XDG_RUNTIME_DIR/holotrace/holotraced.sock, else /run/holotrace/holotraced.sock.
std::string defaultListenAddress();

// Parses the config file. Relative paths resolve against the file's directory. Throws ConfigError.
DaemonConfig loadDaemonConfig(const std::filesystem::path& file);
DaemonConfig parseDaemonConfig(const std::string& json, const std::string& sourceName,
                               const std::filesystem::path& baseDir);

}  // namespace ht::server
