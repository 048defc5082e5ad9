// load_inprocess.cpp - see load_inprocess.h.
#include "bench/load_inprocess.h"

#include <unistd.h>

#include <chrono>
#include <iostream>

#include "gpu/vulkan_context.h"
#include "scene/scene_source.h"
#include "server/display_registry.h"
#include "server/frame_encoding.h"
#include "server/frame_job.h"
#include "server/process_stats.h"
#include "server/scene_library.h"

namespace ht::bench {
namespace {

// The bytes LoadScene would load (scene/scene_source.h); a builtin is its name alone.
SceneSource sceneSource(const std::string& scene) {
  if (scene.rfind("builtin:", 0) == 0) return SceneSource{scene, {}, {}, {}};
  return readSceneSource(scene);
}

InProcessRun timeFrames(server::RenderWorker& worker, const server::FrameJob& base, std::uint64_t frames) {
  InProcessRun run;
  const double cpuBefore = server::readProcessStats(::getpid()).cpuSeconds;
  const auto start = std::chrono::steady_clock::now();
  server::FrameJob job = base;
  for (std::uint64_t i = 0; i < frames; ++i) {
    job.seed = static_cast<std::uint32_t>(i);
    const auto frame = server::renderFrameJob(worker, "baseline", job);
    const auto encoded =
        server::encodeFrame(frame, server::FrameEncoding::Rgba8Srgb, {job.display->config, std::nullopt});
    run.frames += encoded.bytes.empty() ? 0 : 1;
  }
  run.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cpuSeconds = server::readProcessStats(::getpid()).cpuSeconds - cpuBefore;
  return run;
}

}  // namespace

InProcessRun renderInProcess(const std::string& displaysDir, const std::string& display, const std::string& scene,
                             std::uint32_t spp, std::uint64_t frames) {
  gpu::VulkanContext context({-1, false});
  server::RenderWorker worker(context, 2);
  server::SceneLibrary scenes(worker, server::SceneLibraryLimits{});
  server::DisplayRegistry displays(displaysDir);
  displays.reload(std::cerr);
  server::FrameJob job;
  job.display = displays.find(display);
  job.session = scenes.open("baseline", sceneSource(scene));
  job.spp = spp;
  timeFrames(worker, job, 3);  // warm-up: pipelines, per-size buffers
  InProcessRun run = timeFrames(worker, job, frames);
  worker.stop();  // SceneLibrary releases its Renderers after the worker stopped (scene_library.h)
  return run;
}

}  // namespace ht::bench
