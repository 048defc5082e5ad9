// rays_command.cpp - see rays_command.h.
#include "cli/rays_command.h"

#include <array>
#include <chrono>

#include "camera_models/lenticular_model.h"
#include "cli/arguments.h"
#include "cli/cli_app.h"
#include "common/error.h"
#include "frame_io/atomic_output_file.h"
#include "frame_io/ray_table_exr.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::cli {
namespace {

const std::array<OptionSpec, 5> kOptions = {{
    {"--display", "", "SPEC", "display: config.json, visual.json or builtin:NAME (default builtin:portrait)"},
    {"--output", "-o", "FILE.exr", "the ray table (required)"},
    {"--scene", "", "SPEC", "scene whose bounds place \"auto\" cameras (default builtin:showcase, as render)"},
    {"--quilt", "", "", "lenticular displays: the quilt cameras' rays instead of the subpixels'"},
    {"--device", "", "N", "Vulkan device index (see `holotrace info`)"},
}};

constexpr std::uint32_t kTargetsPerChunk = 1u << 22;

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The table: within a view, subpixels side by side (column = perPixel*x + c) and rows from the bottom; views tiled
// like a quilt (view v at tile (v mod columns, v div columns), bottom-left first), as many columns as fit the
// ray-table limit of 16384 entries per side.
struct TableLayout {
  gpu::FrameShape shape;
  std::uint32_t columns = 1, rows = 1;

  explicit TableLayout(const gpu::FrameShape& s) : shape(s) {
    columns = std::max<std::uint32_t>(1, std::min<std::uint32_t>(s.views, kMaxRayTableSize / viewWidth()));
    rows = (s.views + columns - 1) / columns;
  }
  std::uint32_t viewWidth() const { return shape.width * shape.targetsPerPixel; }
  std::uint32_t width() const { return viewWidth() * columns; }
  std::uint32_t height() const { return shape.height * rows; }
  // Entry index of a target (the renderer's target order: x and c, then y, then view).
  std::size_t entry(std::uint64_t target) const {
    const std::uint64_t viewTargets = std::uint64_t(viewWidth()) * shape.height;
    const auto view = static_cast<std::uint32_t>(target / viewTargets);
    const std::uint64_t inView = target % viewTargets;
    const std::uint64_t column = (view % columns) * std::uint64_t(viewWidth()) + inView % viewWidth();
    const std::uint64_t row = (view / columns) * std::uint64_t(shape.height) + inView / viewWidth();
    return static_cast<std::size_t>(row * width() + column);
  }
};

// View phase of every subpixel at its footprint centre (lenticular_model.h, the code raygen runs).
std::vector<float> subpixelPhases(const gpu_shared::LenticularParams& p, std::uint32_t width, std::uint32_t height) {
  std::vector<float> phase(std::size_t(width) * height * 3);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x)
      for (std::uint32_t c = 0; c < 3; ++c) {
        phase[(std::size_t(y) * width + x) * 3 + c] = gpu_shared::lenticular_view_phase(p, x, y, c, glm::vec2(0.5f));
      }
  return phase;
}

}  // namespace

std::string raysHelp() {
  return "Usage: holotrace rays [--display SPEC] -o rays.exr [--scene SPEC] [--quilt] [--device N]\n\n"
         "Generates on the Vulkan device the primary ray of every target of the display (footprint centre) and\n"
         "writes them as an OpenEXR ray table: channels origin.X/Y/Z, direction.X/Y/Z (world units, float32) and,\n"
         "for lenticular panels, the subpixel's view phase (0 = leftmost view). Entry layout: subpixels side by\n"
         "side (column = 3*x + c for lenticular and integral panels, x otherwise), rows from the bottom; several\n"
         "views are tiled like a quilt (view v at tile (v mod C, v div C) from the bottom left, C as many as fit\n"
         "16384 entries). The file reads back as a \"ray-table\" display (docs/configs.md).\n\nOptions:\n" +
         formatOptions(kOptions);
}

int runRays(std::span<const std::string> argv, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  const ParsedArguments args = parseArguments("holotrace rays", kOptions, argv);
  const auto output = args.text("--output");
  if (!output || output->empty()) throw UsageError(usageMessage(args.command(), "missing --output FILE.exr"));
  const auto device = args.unsignedValue("--device", 0, 255);
  frame_io::prepareOutputDirectory(*output);

  const DisplayConfig display = resolveDisplay(args.textOr("--display", "builtin:portrait"));
  const Scene scene = loadScene(args.textOr("--scene", "builtin:showcase"));
  std::shared_ptr<const RayTable> inputTable;
  if (display.model == DisplayModel::RayTable) {
    inputTable = std::make_shared<RayTable>(frame_io::loadDisplayRayTable(display));
  }
  const gpu::DisplayCamera camera = gpu::makeDisplayCamera(
      display, scene.bounds(), args.has("--quilt") ? gpu::CameraPath::Quilt : gpu::CameraPath::Native, inputTable);
  const TableLayout layout(camera.shape);
  const std::uint64_t targets = camera.shape.targets();
  if (layout.width() > kMaxRayTableSize || layout.height() > kMaxRayTableSize) {
    throw UsageError("holotrace rays: the table of '" + display.name + "' would be " + std::to_string(layout.width()) +
                     "x" + std::to_string(layout.height()) + " entries, over the ray-table limit of " +
                     std::to_string(kMaxRayTableSize) + " per side");
  }

  gpu::VulkanContext context({device ? static_cast<int>(*device) : -1, false});
  gpu::Renderer renderer(context, scene);
  out << "display: " << display.name << " (" << displayModelName(display.model) << "), " << camera.shape.views
      << (camera.shape.views == 1 ? " view" : " views") << " of " << camera.shape.width << "x" << camera.shape.height
      << ", " << targets << " rays; device " << context.device().name << "\n";

  RayTable table;
  table.width = layout.width();
  table.height = layout.height();
  table.origins.assign(std::size_t(table.width) * table.height, glm::vec3(0.0f));
  table.directions.assign(table.origins.size(), glm::vec3(0.0f, 0.0f, -1.0f));  // unused tiles: a valid dummy ray
  gpu::RenderSettings settings;
  settings.spp = 1;
  double gpuMs = 0.0;
  for (std::uint64_t first = 0; first < targets; first += kTargetsPerChunk) {
    const auto count = static_cast<std::uint32_t>(std::min<std::uint64_t>(kTargetsPerChunk, targets - first));
    gpu::TraceStats stats;
    const auto rays = renderer.generateRays(camera.camera, settings, first, count, &stats);
    gpuMs += stats.gpuMs;
    for (std::uint32_t i = 0; i < count; ++i) {
      table.origins[layout.entry(first + i)] = rays[i].origin;
      table.directions[layout.entry(first + i)] = rays[i].dir;
    }
  }
  std::vector<float> phase;
  if (const auto* lenticular = std::get_if<gpu_shared::LenticularParams>(&camera.camera)) {
    phase = subpixelPhases(*lenticular, camera.shape.width, camera.shape.height);
  }
  frame_io::writeRayTableExr(*output, table, phase);
  out << "ray generation " << gpuMs << " ms GPU (" << (gpuMs > 0 ? double(targets) / (gpuMs * 1e3) : 0.0)
      << " Mrays/s)\nwrote " << *output << " (" << table.width << "x" << table.height << " entries"
      << (phase.empty() ? "" : ", with view phase") << ") in " << msSince(start) << " ms total\n";
  return kExitOk;
}

}  // namespace ht::cli
