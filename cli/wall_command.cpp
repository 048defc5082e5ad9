// wall_command.cpp - see wall_command.h.
#include "cli/wall_command.h"

#include <array>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <sstream>
#include <thread>

#include "cli/arguments.h"
#include "cli/cli_app.h"
#include "cli/cluster_render.h"
#include "cli/render_command.h"
#include "cli/render_report.h"
#include "cli/wall_layout.h"
#include "cluster/content_hash.h"
#include "cluster/rank_identity.h"
#include "cluster/wall_loop.h"
#include "cluster/wall_report.h"
#include "cluster/work_dispatch.h"
#include "common/error.h"
#include "frame_io/pixel_encoding.h"
#include "frame_io/ray_table_exr.h"
#include "gpu/display_camera.h"
#include "gpu/vulkan_context.h"
#include "present/panel_sink.h"
#include "present/present_error.h"

namespace ht::cli {
namespace {

const char* const kCommand = "holotrace wall";
constexpr std::uint32_t kMaxSpp = 4096, kMaxFrames = 100000000, kMaxSeconds = 86400 * 365;
constexpr std::uint32_t kDefaultFrames = 100, kDefaultSwapTimeoutMs = 100;
constexpr auto kAttachTimeout = std::chrono::seconds(30);
constexpr auto kAttachGrace = std::chrono::milliseconds(2500);  // the sink retries every second
constexpr auto kPresentTimeout = std::chrono::seconds(5);

const std::array<OptionSpec, 16> kSpecs = {{
    {"--display", "", "SPEC", "the wall: config.json or builtin:NAME (default builtin:holovizio-wall-70)"},
    {"--scene", "", "SPEC", "scene: .gltf, .glb, .obj, .off or builtin:NAME (default builtin:showcase)"},
    {"--layout", "", "FILE.json", "which projectors each rank shows, and on which monitor (default: equal groups)"},
    {"--frames", "", "N", "frames to show, 1-100000000 (default 100); frame f uses seed + f"},
    {"--seconds", "", "T", "run for T seconds instead of a frame count (all ranks end on the same frame)"},
    {"--swap-timeout", "", "MS", "longest wait at the swap barrier before flipping without a late rank (default 100)"},
    {"--max-missed", "", "N", "end the job after N timed-out frames in a row (default 0: never)"},
    {"--spp", "", "N", "samples per pixel, 1-4096 (default: the config's spp)"},
    {"--depth", "", "N", "specular bounces after the primary hit, 0-32 (default 4)"},
    {"--seed", "", "N", "sample-pattern seed of frame 0 (default 0)"},
    {"--device", "", "N", "Vulkan device index from `holotrace info` (default: automatic)"},
    {"--x-display", "", "NAME", "X display for every rank without one in the layout (default $DISPLAY)"},
    {"--fifo", "", "", "present with FIFO even where MAILBOX is offered"},
    {"--hold", "", "S", "keep the last frame up S seconds before the windows close (default 0)"},
    {"--verbose", "", "", "also print every rank's times for every frame"},
    {"--debug-rank-delay", "", "R:F:MS", "test hook: rank R sleeps MS ms after rendering frame F (a late rank)"},
}};

struct RankDelay {
  int rank = 0;
  std::uint32_t frame = 0, ms = 0;
};

struct WallOptions {
  RenderOptions render;
  cluster::WallLoopOptions loop;
  std::optional<std::filesystem::path> layout;
  std::string xDisplay;
  bool fifo = false, verbose = false;
  std::uint32_t holdSeconds = 0;
  std::optional<RankDelay> delay;
};

RankDelay parseDelay(const std::string& text) {
  RankDelay d;
  unsigned rank = 0, frame = 0, ms = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%u:%u:%u%c", &rank, &frame, &ms, &tail) != 3 || ms > 600000 || rank > 1000000) {
    throw UsageError(usageMessage(kCommand, "option '--debug-rank-delay' = '" + text +
                                                "': expected RANK:FRAME:MS, e.g. 1:2:500 (MS at most 600000)"));
  }
  d.rank = int(rank);
  d.frame = frame;
  d.ms = ms;
  return d;
}

WallOptions parseWallOptions(std::span<const std::string> args) {
  const ParsedArguments parsed = parseArguments(kCommand, kSpecs, args);
  WallOptions o;
  o.render.displaySpec = parsed.textOr("--display", "builtin:holovizio-wall-70");
  o.render.sceneSpec = parsed.textOr("--scene", o.render.sceneSpec);
  o.render.spp = parsed.unsignedValue("--spp", 1, kMaxSpp);
  o.render.maxDepth = parsed.unsignedValue("--depth", 0, 32);
  o.render.seed = parsed.unsignedValue("--seed", 0, std::numeric_limits<std::uint32_t>::max()).value_or(0);
  if (auto device = parsed.unsignedValue("--device", 0, 255)) o.render.deviceIndex = int(*device);
  if (parsed.has("--frames") && parsed.has("--seconds"))
    throw UsageError(usageMessage(kCommand, "give '--frames' or '--seconds', not both"));
  o.loop.seconds = parsed.numberValue("--seconds", 0.001, kMaxSeconds);
  if (!o.loop.seconds) o.loop.frames = parsed.unsignedValue("--frames", 1, kMaxFrames).value_or(kDefaultFrames);
  o.loop.deadlineUs =
      std::int64_t(parsed.unsignedValue("--swap-timeout", 1, 600000).value_or(kDefaultSwapTimeoutMs)) * 1000;
  o.loop.maxMissed = parsed.unsignedValue("--max-missed", 0, kMaxFrames).value_or(0);
  if (auto layout = parsed.text("--layout")) o.layout = *layout;
  o.xDisplay = parsed.textOr("--x-display", "");
  o.fifo = parsed.has("--fifo");
  o.verbose = parsed.has("--verbose");
  o.holdSeconds = parsed.unsignedValue("--hold", 0, 3600).value_or(0);
  if (auto delay = parsed.text("--debug-rank-delay")) o.delay = parseDelay(*delay);
  return o;
}

// Renders this rank's projectors' views of a frame into one tiled panel image (wall_layout.h).
class TiledViews {
 public:
  TiledViews(gpu::Renderer& renderer, const gpu::DisplayCamera& camera, const gpu::RenderSettings& settings,
             const RankScreen& screen)
      : renderer_(renderer), camera_(camera), settings_(settings), screen_(screen) {
    const gpu::FrameShape& shape = camera.shape;
    image_.width = screen.columns * shape.width;
    image_.height = screen.rows() * shape.height;
    for (std::size_t i = 0; i < screen.projectors.size(); ++i) {
      const bool extends = !runs_.empty() && screen.projectors[i] == screen.projectors[i - 1] + 1;
      if (extends)
        ++runs_.back().count;
      else
        runs_.push_back({i, screen.projectors[i], 1});
    }
  }
  std::uint32_t width() const { return image_.width; }
  std::uint32_t height() const { return image_.height; }

  present::PanelFrame render(std::uint32_t frame) {
    image_.rgba.assign(std::size_t(image_.width) * image_.height * 4, 0);
    for (const Run& run : runs_) {
      gpu::RenderSettings s = settings_;
      s.seed = settings_.seed + frame;
      s.region = {run.firstView, run.count, 0, 0};
      const gpu::RenderResult result = renderer_.render(camera_.camera, s);
      for (std::uint32_t v = 0; v < run.count; ++v) place(run.firstTile + v, result, v);
    }
    return image_;
  }

 private:
  struct Run {
    std::size_t firstTile;
    std::uint32_t firstView, count;
  };

  void place(std::size_t tile, const gpu::RenderResult& result, std::uint32_t v) {
    const std::size_t viewFloats = std::size_t(result.width) * result.height * 4;
    const std::vector<std::uint8_t> bytes =
        frame_io::encodeRgba8Srgb(std::span<const float>(result.rgba).subspan(std::size_t(v) * viewFloats, viewFloats));
    const std::size_t x0 = (tile % screen_.columns) * result.width, y0 = (tile / screen_.columns) * result.height;
    const std::size_t rowBytes = std::size_t(result.width) * 4;
    for (std::uint32_t y = 0; y < result.height; ++y) {
      std::copy_n(bytes.data() + y * rowBytes, rowBytes, image_.rgba.data() + ((y0 + y) * image_.width + x0) * 4);
    }
  }

  gpu::Renderer& renderer_;
  const gpu::DisplayCamera& camera_;
  const gpu::RenderSettings& settings_;
  const RankScreen& screen_;
  std::vector<Run> runs_;
  present::PanelFrame image_;
};

present::PanelSinkOptions sinkOptions(const WallOptions& o, const RankScreen& screen, const TiledViews& tiles) {
  present::PanelSinkOptions s;
  s.xDisplay = screen.xDisplay.value_or(o.xDisplay);
  s.panel.screenWidth = tiles.width();
  s.panel.screenHeight = tiles.height();
  s.panel.output = screen.monitor;
  s.panel.geometry = screen.geometry;
  s.presentMode = o.fifo ? present::PresentModeChoice::Fifo : present::PresentModeChoice::Auto;
  s.vulkanDevice = o.render.deviceIndex;
  return s;
}

// Waits until the sink shows its window. A failed attach (no such monitor, no X server) ends the wait after the
// sink's first retry, so a wrong layout fails in seconds, not after kAttachTimeout.
void waitForAttach(const present::PanelSink& sink, const std::string& prefix) {
  const auto start = std::chrono::steady_clock::now();
  while (!sink.stats().attached) {
    const auto waited = std::chrono::steady_clock::now() - start;
    const std::string error = sink.stats().lastError;
    if (waited > kAttachTimeout || (!error.empty() && waited > kAttachGrace)) {
      throw present::PresentError(
          "no window on the wall's monitor: " +
          (error.empty() ? "none after " + std::to_string(kAttachTimeout.count()) + " s" : error));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const present::PanelSinkStats s = sink.stats();
  std::ostringstream line;
  line << prefix << "showing on monitor " << s.monitor->monitor << " " << present::describeRect(s.monitor->rect) << " ("
       << s.monitor->rule << ", " << s.swapchain.presentMode << ")\n";
  std::cout << line.str() << std::flush;
}

// Submits the frame and waits until the sink has presented it; returns when (job clock), or -1 if it was not shown.
std::int64_t presentAndWait(present::PanelSink& sink, present::PanelFrame frame, const cluster::JobClock& clock,
                            const std::string& prefix) {
  frame.done = present::Clock::now();
  const std::int64_t doneUs = clock.toUs(frame.done);
  const std::uint64_t sequence = sink.submit(std::move(frame));
  const auto until = std::chrono::steady_clock::now() + kPresentTimeout;
  while (std::chrono::steady_clock::now() < until) {
    const present::PanelSinkStats s = sink.stats();
    if (s.lastPresentedSequence >= sequence) { return doneUs + std::int64_t(s.lastPresentLatencyMs * 1000.0); }
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
  std::cerr << prefix << "warning: frame not shown within " << kPresentTimeout.count()
            << " s: " << sink.stats().lastError << "\n";
  return -1;
}

std::string msText(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f ms", ms);
  return text;
}

void printSummary(std::ostream& out, const cluster::WallSummary& s, const WallOptions& o) {
  out << "wall: " << s.ranks.size() << " rank(s), " << s.frames << " frame(s), swap deadline "
      << msText(double(o.loop.deadlineUs) / 1000.0) << "\n";
  for (std::size_t r = 0; r < s.ranks.size(); ++r) {
    const cluster::WallRankSummary& k = s.ranks[r];
    out << "  rank " << r << ": presented " << k.presented << " (on time " << k.onTime << ", timed out " << k.timedOut
        << "), late " << k.late << ", skipped " << k.skipped << "; median render " << msText(k.renderMedianMs)
        << ", barrier wait " << msText(k.waitMedianMs) << ", present " << msText(k.presentMedianMs) << "; totals "
        << msText(k.renderTotalMs) << " / " << msText(k.waitTotalMs) << " / " << msText(k.presentTotalMs) << "\n";
  }
  char line[256];
  std::snprintf(line, sizeof line,
                "  swap: %u frame(s) shown by every rank on time; barrier cost median %.1f us (the last rank's wait), "
                "release skew median %.1f us, flip skew median %.1f us (max %.1f us)\n",
                s.syncedFrames, s.barrierCostMedianUs, s.releaseSkewMedianUs, s.flipSkewMedianUs, s.flipSkewMaxUs);
  out << line;
  for (const cluster::WallLateEvent& e : s.late) {
    out << "  late: rank " << e.rank << ", frame " << e.frame << ", by " << msText(e.lateByMs) << "\n";
  }
}

void printFrames(std::ostream& out, std::span<const cluster::WallFrameRecord> all, std::size_t ranks) {
  const std::size_t frames = ranks ? all.size() / ranks : 0;
  for (std::size_t f = 0; f < frames; ++f) {
    for (std::size_t r = 0; r < ranks; ++r) {
      const cluster::WallFrameRecord& k = all[r * frames + f];
      char line[200];
      std::snprintf(line, sizeof line,
                    "  frame %zu rank %zu: %s, render %.2f ms, entry %.3f ms, wait %.3f ms, flip %.3f ms, present "
                    "%.2f ms\n",
                    f, r, cluster::wallOutcomeName(k.outcome), double(k.renderUs) / 1000.0, double(k.entryUs) / 1000.0,
                    double(k.releaseUs - k.entryUs) / 1000.0, double(k.flipUs) / 1000.0, double(k.presentUs) / 1000.0);
      out << line;
    }
  }
}

std::string wallSettingsDigest(const gpu::RenderSettings& settings, const WallLayout& layout, const WallOptions& o) {
  cluster::ContentHash hash;
  hash.add(cluster::settingsDigest(settings)).add(describeWallLayout(layout));
  hash.addValue(o.loop.deadlineUs).addValue(o.loop.maxMissed).addValue(o.loop.frames.value_or(0));
  hash.addValue(o.loop.seconds.value_or(0.0));
  return hash.hex();
}

int runWallOnRank(cluster::Communicator& comm, const WallOptions& o, std::ostream& out) {
  const bool root = comm.rank() == 0;
  std::ostream silent(nullptr);
  std::ostream& log = root ? out : silent;
  const std::string prefix = rankPrefix(comm);

  const DisplayConfig display = resolveDisplay(o.render.displaySpec);
  log << "display: " << display.name << " (" << displayModelName(display.model) << ", " << o.render.displaySpec
      << ")\n";
  const SharedScene shared = shareScene(comm, o.render.sceneSpec);
  std::shared_ptr<const RayTable> rayTable;
  if (display.model == DisplayModel::RayTable)
    rayTable = std::make_shared<RayTable>(frame_io::loadDisplayRayTable(display));
  const gpu::DisplayCamera camera =
      makeDisplayCamera(display, shared.scene.bounds(), gpu::CameraPath::Native, rayTable);
  const std::uint32_t views = camera.shape.views, ranks = std::uint32_t(comm.size());
  const WallLayout layout = o.layout ? loadWallLayout(*o.layout, views, ranks) : defaultWallLayout(views, ranks);
  gpu::RenderSettings settings = makeRenderSettings(o.render, display);
  settings.progress = nullptr;
  cluster::checkRankIdentities(comm, {cluster::buildId(), cluster::displayDigest(display.name, camera), shared.digest,
                                      wallSettingsDigest(settings, layout, o)});

  gpu::VulkanContext context({o.render.deviceIndex, false});
  if (root) printDevice(log, context.device());
  const auto renderer = buildRenderer(log, context, shared.scene, shared.loadMs);
  const RankScreen& screen = layout.ranks[std::size_t(comm.rank())];
  TiledViews tiles(*renderer, camera, settings, screen);
  log << "wall: " << views << " projector view(s) of " << camera.shape.width << "x" << camera.shape.height << " over "
      << ranks << " rank(s) (" << layout.source << "), spp " << settings.spp << "\n";

  tiles.render(0);  // warm-up, not shown: the first render pays for pipelines and buffers, not for the frame
  present::PanelSink sink(sinkOptions(o, screen, tiles));
  waitForAttach(sink, prefix);
  cluster::JobClock clock;
  present::PanelFrame frame;
  cluster::WallCallbacks callbacks;
  callbacks.render = [&](std::uint32_t f) {
    frame = tiles.render(f);
    if (o.delay && o.delay->rank == comm.rank() && o.delay->frame == f)
      std::this_thread::sleep_for(std::chrono::milliseconds(o.delay->ms));
    const char* kill = std::getenv(cluster::kKillRankVariable);
    if (kill && f == 0 && std::atoi(kill) == comm.rank()) std::raise(SIGKILL);
  };
  callbacks.present = [&](std::uint32_t) { return presentAndWait(sink, std::move(frame), clock, prefix); };
  callbacks.warn = [&](const std::string& line) { std::cerr << prefix << line << "\n" << std::flush; };
  const std::vector<cluster::WallFrameRecord> mine = cluster::runWallLoop(comm, o.loop, callbacks, clock);
  const std::vector<cluster::WallFrameRecord> all = cluster::gatherWallRecords(comm, mine);
  if (root) {
    printSummary(log, cluster::summarizeWall(all, comm.size()), o);
    if (o.verbose) printFrames(log, all, std::size_t(comm.size()));
    log << std::flush;
  }
  std::this_thread::sleep_for(std::chrono::seconds(o.holdSeconds));
  comm.barrier();  // every rank's last frame stayed up for the hold
  return kExitOk;
}

}  // namespace

std::string wallHelp() {
  return std::string(
             "Usage: mpirun -np N holotrace wall [options]\n\n"
             "Live wall mode (docs/CLUSTER.md): each rank renders its own group of the display's projectors (views)\n"
             "with its own renderer (rank 0 broadcasts the scene once; every rank builds its own BVH), shows them in\n"
             "one window on its monitor (the projectors' images tiled 1:1, as --layout says), and all ranks flip\n"
             "together behind a swap barrier: render -> barrier (polled against --swap-timeout) -> present. A rank\n"
             "that falls behind is reported (rank, frame, lateness) and the others flip without it; it skips to the\n"
             "frame the others are at. A rank that dies ends every rank. Without mpirun it runs as one rank.\n"
             "At the end rank 0 prints every rank's render / barrier wait / present times, the barrier's cost and\n"
             "the flip skew between ranks.\n\nOptions:\n") +
         formatOptions(kSpecs) +
         "\nExamples:\n"
         "  mpirun -np 4 holotrace wall --display builtin:holovizio-wall-70 --scene model.glb --layout wall.json\n"
         "  mpirun -np 2 holotrace wall --display wall.json --seconds 60 --swap-timeout 50 --verbose\n";
}

int runWall(std::span<const std::string> args, std::ostream& out) {
  if (wantsHelp(args)) {
    out << wallHelp();
    return kExitOk;
  }
  const WallOptions options = parseWallOptions(args);
  return runOnEveryRank([&](cluster::Communicator& comm) { return runWallOnRank(comm, options, out); });
}

}  // namespace ht::cli
