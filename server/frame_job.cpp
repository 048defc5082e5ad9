// frame_job.cpp - see frame_job.h. Same camera dispatch as `holotrace render` (cli/render_command.cpp).
#include "server/frame_job.h"

#include "camera_models/lenticular_params.h"
#include "camera_models/pinhole_params.h"

namespace ht::server {

PanelSize framePanelSize(const DisplayConfig& display) {
  if (display.model == DisplayModel::Lenticular && display.calibration) {
    return {display.calibration->screenW, display.calibration->screenH};
  }
  return {display.pinhole.width.value_or(1280), display.pinhole.height.value_or(720)};
}

DisplayConfig displayForSession(const DisplayConfig& display, const SceneSession& session) {
  DisplayConfig config = display;
  if (session.cameraOverride.target) config.camera.target = session.cameraOverride.target;
  if (session.cameraOverride.size) config.camera.size = session.cameraOverride.size;
  return config;
}

gpu::RenderResult renderFrameJob(RenderWorker& worker, const std::string& client, const FrameJob& job) {
  const DisplayConfig config = displayForSession(job.display->config, *job.session);
  gpu::RenderSettings settings;
  settings.spp = job.spp ? job.spp : config.spp;
  settings.seed = job.seed;
  gpu::RenderResult result;
  const SceneContent& content = *job.session->content;
  worker
      .submit(client,
              [&](gpu::VulkanContext&) {
                const Bounds3 bounds = content.scene.bounds();
                result = config.model == DisplayModel::Pinhole
                             ? content.renderer->renderPinhole(makePinholeParams(config, bounds), settings)
                             : content.renderer->renderLenticular(makeLenticularParams(config, bounds), settings);
              })
      .get();
  return result;
}

}  // namespace ht::server
