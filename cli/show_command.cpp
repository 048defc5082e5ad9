// show_command.cpp - see show_command.h. The frame is the one `holotrace render -o` writes (native camera path, same
// settings and seed), shown 1:1 through present::PanelSink.
#include "cli/show_command.h"

#include <signal.h>

#include <array>
#include <chrono>
#include <ctime>
#include <limits>

#include "cli/arguments.h"
#include "cli/cli_app.h"
#include "cli/render_report.h"
#include "common/error.h"
#include "common/parallel_chunks.h"
#include "frame_io/quilt_file.h"
#include "frame_io/ray_table_exr.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "present/panel_sink.h"
#include "scene/scene.h"

namespace ht::cli {
namespace {

const char* const kCommand = "holotrace show";
constexpr std::uint32_t kMaxSpp = 4096;
constexpr std::uint32_t kMaxSeconds = 86400 * 365;

const std::array<OptionSpec, 11> kSpecs = {{
    {"--display", "", "SPEC", "display: config.json, visual.json or builtin:NAME (default builtin:portrait)"},
    {"--scene", "", "SPEC",
     "scene: .gltf, .glb, .obj, .off or builtin:NAME (default builtin:showcase), or a quilt image .png / .exr "
     "(e.g. hologram_qs8x6a0.75.png: shown interleaved as `holotrace interleave` writes it; --spp, --seed unused)"},
    {"--spp", "", "N", "samples per subpixel / pixel, 1-4096 (default: the config's spp)"},
    {"--seed", "", "N", "sample-pattern seed (default 0, as `holotrace render`)"},
    {"--x-display", "", "NAME", "X display to show on, e.g. :0 (default $DISPLAY)"},
    {"--monitor", "", "NAME", "the panel's RandR output or monitor name (default: found by EDID 'LKG' and size)"},
    {"--geometry", "", "WxH+X+Y", "the panel's rectangle on the X screen (default: found by EDID 'LKG' and size)"},
    {"--fullscreen", "", "", "ask the window manager for fullscreen instead of an override-redirect window"},
    {"--fifo", "", "", "present with FIFO even where MAILBOX is offered"},
    {"--device", "", "N", "Vulkan device index from `holotrace info` (default: automatic)"},
    {"--seconds", "", "N", "stop after N seconds (default: run until Ctrl-C / SIGTERM)"},
}};

struct ShowOptions {
  std::string displaySpec = "builtin:portrait";
  std::string sceneSpec = "builtin:showcase";
  std::optional<std::uint32_t> spp;
  std::uint32_t seed = 0;
  int deviceIndex = -1;
  std::optional<std::uint32_t> seconds;
  present::PanelSinkOptions sink;
};

ShowOptions parseShowOptions(std::span<const std::string> args) {
  const ParsedArguments parsed = parseArguments(kCommand, kSpecs, args);
  ShowOptions o;
  o.displaySpec = parsed.textOr("--display", o.displaySpec);
  o.sceneSpec = parsed.textOr("--scene", o.sceneSpec);
  o.spp = parsed.unsignedValue("--spp", 1, kMaxSpp);
  o.seed = parsed.unsignedValue("--seed", 0, std::numeric_limits<std::uint32_t>::max()).value_or(0);
  if (auto device = parsed.unsignedValue("--device", 0, 255)) o.deviceIndex = int(*device);
  o.seconds = parsed.unsignedValue("--seconds", 1, kMaxSeconds);
  o.sink.xDisplay = parsed.textOr("--x-display", "");
  o.sink.panel.output = parsed.text("--monitor");
  if (auto geometry = parsed.text("--geometry")) {
    try {
      o.sink.panel.geometry = present::parseGeometry(*geometry);
    } catch (const present::PresentError& e) {
      throw UsageError(usageMessage(kCommand, std::string("option '--geometry': ") + e.what()));
    }
  }
  if (o.sink.panel.output && o.sink.panel.geometry) {
    throw UsageError(usageMessage(kCommand, "give '--monitor' or '--geometry', not both"));
  }
  if (parsed.has("--fullscreen")) o.sink.window = present::WindowMode::Fullscreen;
  if (parsed.has("--fifo")) o.sink.presentMode = present::PresentModeChoice::Fifo;
  o.sink.vulkanDevice = o.deviceIndex;
  o.sink.transfer = present::frameTransferFromEnvironment();
  return o;
}

// A quilt image interleaved for the panel, as `holotrace interleave` and the daemon's quilt content do it (the vendor's
// view filter; frame_io/quilt_file.h).
present::PanelFrame quiltPanelFrame(const ShowOptions& options, const DisplayConfig& display, std::ostream& out) {
  const frame_io::InterleavedQuilt panel =
      frame_io::interleaveQuiltFile(options.sceneSpec, display, {}, QuiltViewFilter::VendorLerp, hardwareThreads());
  const QuiltLayout& layout = panel.layout.layout;
  out << "quilt " << layout.columns << "x" << layout.rows << " of " << layout.tileWidth << "x" << layout.tileHeight
      << " (layout from the " << panel.layout.source << ") interleaved for " << panel.width << "x" << panel.height
      << "\n";
  return present::panelFrame({panel.width, panel.height, 1, panel.rgba}, {display, std::nullopt});
}

present::PanelFrame renderPanelFrame(const ShowOptions& options, const DisplayConfig& display, std::ostream& out) {
  if (frame_io::isQuiltImageFile(options.sceneSpec)) return quiltPanelFrame(options, display, out);
  const Scene scene = loadScene(options.sceneSpec);
  std::shared_ptr<const RayTable> rayTable;
  if (display.model == DisplayModel::RayTable)
    rayTable = std::make_shared<RayTable>(frame_io::loadDisplayRayTable(display));
  const gpu::DisplayCamera camera = makeDisplayCamera(display, scene.bounds(), gpu::CameraPath::Native, rayTable);
  gpu::VulkanContext context({options.deviceIndex, false});
  gpu::Renderer renderer(context, scene);
  gpu::RenderSettings settings;
  settings.spp = options.spp.value_or(display.spp);
  settings.seed = options.seed;
  const gpu::RenderResult frame = renderer.render(camera.camera, settings);
  out << "rendered " << frame.width << "x" << frame.height
      << (frame.views > 1 ? " x " + std::to_string(frame.views) + " views" : "") << " at spp " << settings.spp << " in "
      << formatMs(frame.totalMs) << "\n";
  return present::panelFrame({frame.width, frame.height, frame.views, frame.rgba}, {display, camera.quilt});
}

// Blocks SIGINT and SIGTERM in this thread (and in the threads it starts) while alive, so they are taken with
// sigtimedwait instead of ending the process; the previous mask comes back at scope end.
class StopSignals {
 public:
  StopSignals() {
    sigemptyset(&set_);
    sigaddset(&set_, SIGINT);
    sigaddset(&set_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set_, &previous_);
  }
  ~StopSignals() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  // True if a stop signal arrived within `ms`.
  bool wait(long ms) {
    timespec t{ms / 1000, (ms % 1000) * 1'000'000};
    return sigtimedwait(&set_, nullptr, &t) > 0;
  }

 private:
  sigset_t set_{}, previous_{};
};

}  // namespace

std::string showHelp() {
  return std::string(
             "Usage: holotrace show [options]\n\n"
             "Renders the display's frame (as `holotrace render -o` would) and shows it 1:1 on the panel's monitor "
             "until\n"
             "Ctrl-C or SIGTERM. The monitor is the one named by --monitor / --geometry, else by the display config's\n"
             "\"panel\" section (output or geometry), else the one whose EDID name\n"
             "starts with LKG and whose size is the frame's, else the only monitor of that size (docs/DISPLAY.md).\n"
             "If the panel or the X server goes away, the frame comes back when they do.\n\nOptions:\n") +
         formatOptions(kSpecs);
}

int runShow(std::span<const std::string> args, std::ostream& out) {
  if (wantsHelp(args)) {
    out << showHelp();
    return kExitOk;
  }
  ShowOptions options = parseShowOptions(args);
  const DisplayConfig display = resolveDisplay(options.displaySpec);
  out << "display: " << display.name << " (" << displayModelName(display.model) << ", " << options.displaySpec << ")\n";
  present::PanelFrame frame = renderPanelFrame(options, display, out);
  options.sink.panel.screenWidth = frame.width;
  options.sink.panel.screenHeight = frame.height;
  options.sink.panel = present::withPlacement(options.sink.panel, display.panel);  // --monitor/--geometry win

  StopSignals signals;  // before the sink's thread starts, so it inherits the mask
  present::PanelSink sink(options.sink);
  sink.submit(std::move(frame));
  const auto start = std::chrono::steady_clock::now();
  bool announced = false;
  while (true) {
    const bool stop = signals.wait(100);
    present::PanelSinkStats s = sink.stats();
    if (!announced && s.presented > 0 && s.monitor) {
      out << "showing on monitor " << s.monitor->monitor << " " << present::describeRect(s.monitor->rect) << " ("
          << s.monitor->rule << ", " << s.swapchain.presentMode << ", " << s.swapchain.format << ")"
          << (options.seconds ? "" : "; Ctrl-C to stop") << "\n"
          << std::flush;
      announced = true;
    }
    const bool timeUp =
        options.seconds && std::chrono::steady_clock::now() - start >= std::chrono::seconds(*options.seconds);
    if (stop || timeUp) {
      out << "stopped: presented " << s.presented << " time(s), " << s.attachments << " attachment(s)\n";
      if (s.presented == 0) throw present::PresentError("the frame was never shown: " + s.lastError);
      return kExitOk;
    }
  }
}

}  // namespace ht::cli
