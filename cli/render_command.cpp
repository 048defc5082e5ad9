// render_command.cpp - see render_command.h.
#include "cli/render_command.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include <unistd.h>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/pinhole_params.h"
#include "cli/cli_app.h"
#include "cli/frame_outputs.h"
#include "cli/output_paths.h"
#include "cli/render_report.h"
#include "cli/view_phase_debug.h"
#include "common/error.h"
#include "frame_io/atomic_output_file.h"
#include "frame_io/ray_table_exr.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::cli {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

gpu::RenderSettings makeSettings(const RenderOptions& options, const DisplayConfig& display) {
  gpu::RenderSettings settings;
  settings.spp = options.spp.value_or(display.spp);
  if (options.maxDepth) settings.maxDepth = *options.maxDepth;
  settings.forceAllFeatures = options.noSpecialize;
  settings.seed = options.seed;
  settings.filter = options.filter;
  settings.refineSpp = options.refineSpp;
  settings.refineContrast = options.refineContrast;
  if (isatty(STDERR_FILENO)) {  // a progress line on a terminal only; logs and pipes get the final report
    settings.progress = [](double done) { std::fprintf(stderr, "\rrender %5.1f %%", 100.0 * done); };
  }
  return settings;
}

const char* filterName(gpu::SampleFilter filter) {
  switch (filter) {
    case gpu::SampleFilter::Tent: return "tent";
    case gpu::SampleFilter::Gaussian: return "gaussian";
    default: return "box";
  }
}

// Builds the BVH and uploads the scene, then prints the scene and BVH reports.
std::unique_ptr<gpu::Renderer> buildRenderer(std::ostream& out, gpu::VulkanContext& context, const Scene& scene,
                                             double loadMs) {
  const auto start = Clock::now();
  auto renderer = std::make_unique<gpu::Renderer>(context, scene);
  const double uploadMs = msSince(start);
  printScene(out, scene, renderer->features());
  out << "  loaded in " << formatMs(loadMs) << "\n";
  printBvh(out, renderer->bvhReport());
  out << "  BVH build + upload " << formatMs(uploadMs) << "\n";
  return renderer;
}

gpu::RenderResult renderAndReport(std::ostream& out, gpu::Renderer& renderer, const gpu::DisplayCamera& camera,
                                  const gpu::RenderSettings& settings) {
  const gpu::FrameShape& shape = camera.shape;
  out << "render: " << shape.views << (shape.views == 1 ? " view" : " views") << " of " << shape.width << "x"
      << shape.height << ", " << shape.targets() << " targets, spp " << settings.spp << ", filter "
      << filterName(settings.filter) << ", depth " << settings.maxDepth << ", seed " << settings.seed
      << (settings.forceAllFeatures ? ", all features forced on" : "");
  if (settings.refineSpp > 0)
    out << ", refine at spp " << settings.refineSpp << " from contrast " << settings.refineContrast;
  out << "\n";
  gpu::RenderResult frame = renderer.render(camera.camera, settings);
  if (settings.progress) std::fprintf(stderr, "\r");
  printFrame(out, frame);
  if (frame.nonFiniteSamples > 0) {
    out << "warning: " << frame.nonFiniteSamples << " samples were NaN/Inf and were written as 0 (a renderer bug)\n";
  }
  return frame;
}

int runViewPhaseDebug(std::ostream& out, const RenderOptions& options, const DisplayConfig& display,
                      const OutputPaths& paths, Clock::time_point start) {
  if (display.model != DisplayModel::Lenticular) {
    throw UsageError("holotrace render: --debug views: display '" + display.name + "' is a '" +
                     std::string(displayModelName(display.model)) +
                     "' display; view phases exist for lenticular displays only");
  }
  (void)options;
  const gpu::RenderResult frame = renderViewPhaseDebug(makeLenticularParams(display, Bounds3{}));
  out << "debug views: channel value = view phase t of the subpixel (0 = leftmost view), no tracing, "
      << formatMs(frame.totalMs) << "\n";
  writeFrameOutputs(out, paths, frame, {display, std::nullopt}, frame_io::ViewLayout::Auto);
  out << "total " << formatMs(msSince(start)) << "\n";
  return kExitOk;
}

}  // namespace

int runRender(std::span<const std::string> args, std::ostream& out) {
  const auto start = Clock::now();
  const RenderOptions options = parseRenderOptions(args);

  const DisplayConfig display = resolveDisplay(options.displaySpec);
  const OutputPaths paths = resolveOutputPaths(options, display.name);
  if (paths.png) frame_io::prepareOutputDirectory(*paths.png);  // fail before the render, not after it
  if (paths.exr) frame_io::prepareOutputDirectory(*paths.exr);
  out << "display: " << display.name << " (" << displayModelName(display.model) << ", " << options.displaySpec << ")\n";

  if (options.debugViews) return runViewPhaseDebug(out, options, display, paths, start);

  const auto loadStart = Clock::now();
  const Scene scene = loadScene(options.sceneSpec);
  const double loadMs = msSince(loadStart);
  std::shared_ptr<const RayTable> rayTable;
  if (display.model == DisplayModel::RayTable) {
    rayTable = std::make_shared<RayTable>(frame_io::loadDisplayRayTable(display));
  }
  const gpu::DisplayCamera camera = makeDisplayCamera(display, scene.bounds(), options.cameraPath, rayTable);
  const frame_io::FrameDisplay frameDisplay{display, camera.quilt};
  checkViewLayout(frameDisplay, camera.shape.views, options.layout);  // before the render, not after it

  gpu::VulkanContext context({options.deviceIndex, options.validation});
  printDevice(out, context.device());
  const auto renderer = buildRenderer(out, context, scene, loadMs);

  const gpu::RenderResult frame = renderAndReport(out, *renderer, camera, makeSettings(options, display));
  writeFrameOutputs(out, paths, frame, frameDisplay, options.layout);
  if (options.validation) out << "validation messages: " << context.validationMessageCount() << "\n";
  out << "total " << formatMs(msSince(start)) << "\n";
  return kExitOk;
}

}  // namespace ht::cli
