// frame_job.h - one display frame of one scene session, rendered on the render worker.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "gpu/renderer.h"
#include "server/display_registry.h"
#include "server/render_worker.h"
#include "server/scene_library.h"

namespace ht::server {

struct FrameJob {
  std::shared_ptr<const SceneSession> session;
  std::shared_ptr<const RegisteredDisplay> display;
  std::uint32_t spp = 0;  // 0 = display default
  std::uint32_t seed = 0;
};

struct PanelSize {
  std::uint32_t width = 0, height = 0;
};

// The image size a frame of `display` has (panel for lenticular, pinhole image size otherwise).
PanelSize framePanelSize(const DisplayConfig& display);

// The display with the session's UpdateScene camera placement applied.
DisplayConfig displayForSession(const DisplayConfig& display, const SceneSession& session);

// Queues the frame for `client` and waits for it. Throws what the worker or renderer threw.
gpu::RenderResult renderFrameJob(RenderWorker& worker, const std::string& client, const FrameJob& job);

}  // namespace ht::server
