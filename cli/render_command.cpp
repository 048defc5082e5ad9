// render_command.cpp - see render_command.h.
#include "cli/render_command.h"

#include <chrono>
#include <memory>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/pinhole_params.h"
#include "cli/atomic_output_file.h"
#include "cli/cli_app.h"
#include "cli/image_file_writer.h"
#include "cli/output_paths.h"
#include "cli/render_report.h"
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
  return settings;
}

gpu::RenderResult renderFrame(gpu::Renderer& renderer, const DisplayConfig& display, const Scene& scene,
                              const gpu::RenderSettings& settings) {
  if (display.model == DisplayModel::Pinhole) {
    return renderer.renderPinhole(makePinholeParams(display, scene.bounds()), settings);
  }
  return renderer.renderLenticular(makeLenticularParams(display, scene.bounds()), settings);
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

gpu::RenderResult renderAndReport(std::ostream& out, gpu::Renderer& renderer, const DisplayConfig& display,
                                  const Scene& scene, const gpu::RenderSettings& settings) {
  out << "render: spp " << settings.spp << ", depth " << settings.maxDepth << ", seed " << settings.seed
      << (settings.forceAllFeatures ? ", all features forced on" : "") << "\n";
  gpu::RenderResult frame = renderFrame(renderer, display, scene, settings);
  printFrame(out, frame);
  if (frame.nonFiniteSamples > 0) {
    out << "warning: " << frame.nonFiniteSamples << " samples were NaN/Inf and were written as 0 (a renderer bug)\n";
  }
  return frame;
}

void writeOutputs(std::ostream& out, const OutputPaths& paths, const gpu::RenderResult& frame) {
  const RgbaImageView image{frame.width, frame.height, frame.rgba};
  if (paths.png) {
    writeImageFile(*paths.png, image, ImageFormat::Png8Srgb);
    out << "wrote " << paths.png->string() << " (" << frame.width << "x" << frame.height << ", 8-bit sRGB PNG)\n";
  }
  if (paths.exr) {
    writeImageFile(*paths.exr, image, ImageFormat::ExrHalf);
    out << "wrote " << paths.exr->string() << " (" << frame.width << "x" << frame.height << ", linear half EXR)\n";
  }
}

}  // namespace

int runRender(std::span<const std::string> args, std::ostream& out) {
  const auto start = Clock::now();
  const RenderOptions options = parseRenderOptions(args);

  const DisplayConfig display = resolveDisplay(options.displaySpec);
  const OutputPaths paths = resolveOutputPaths(options, display.name);
  if (paths.png) prepareOutputDirectory(*paths.png);  // fail before the render, not after it
  if (paths.exr) prepareOutputDirectory(*paths.exr);
  out << "display: " << display.name << " (" << displayModelName(display.model) << ", " << options.displaySpec
      << ")\n";

  const auto loadStart = Clock::now();
  const Scene scene = loadScene(options.sceneSpec);
  const double loadMs = msSince(loadStart);

  gpu::VulkanContext context({options.deviceIndex, options.validation});
  printDevice(out, context.device());
  const auto renderer = buildRenderer(out, context, scene, loadMs);

  const gpu::RenderResult frame = renderAndReport(out, *renderer, display, scene, makeSettings(options, display));
  writeOutputs(out, paths, frame);
  if (options.validation) out << "validation messages: " << context.validationMessageCount() << "\n";
  out << "total " << formatMs(msSince(start)) << "\n";
  return kExitOk;
}

}  // namespace ht::cli
