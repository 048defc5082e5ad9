// frame_job.cpp - see frame_job.h. Same camera dispatch as `holotrace render` (gpu/display_camera.h).
#include "server/frame_job.h"

#include "server/distributed_frames.h"

namespace ht::server {

gpu::FrameShape displayFrameShape(const RegisteredDisplay& display, gpu::CameraPath path) {
  return gpu::makeDisplayCamera(display.config, Bounds3{}, path, display.rayTable).shape;
}

DisplayConfig displayForSession(const DisplayConfig& display, const SceneSession& session) {
  DisplayConfig config = display;
  if (session.cameraOverride.target) config.camera.target = session.cameraOverride.target;
  if (session.cameraOverride.size) config.camera.size = session.cameraOverride.size;
  if (config.projectorArray) {
    if (session.observerDistance) config.projectorArray->observerDistance = *session.observerDistance;
    if (session.observerHeight) config.projectorArray->observerHeight = *session.observerHeight;
  }
  return config;
}

gpu::DisplayCamera jobCamera(const FrameJob& job) {
  const DisplayConfig config = displayForSession(job.display->config, *job.session);
  return gpu::makeDisplayCamera(config, job.session->content->loadBounds, job.path, job.display->rayTable);
}

namespace {

gpu::RenderSettings jobSettings(const FrameJob& job) {
  gpu::RenderSettings settings;
  settings.spp = job.spp ? job.spp : job.display->config.spp;
  settings.seed = job.seed;
  settings.refineSpp = job.refineSpp;
  settings.refineContrast = job.refineContrast;
  settings.reuse = job.reuse;
  return settings;
}

}  // namespace

gpu::RenderResult accumulateFrameJob(RenderWorker& worker, const std::string& client, const FrameJob& job,
                                     gpu::Accumulator& accumulator) {
  gpu::RenderSettings settings = jobSettings(job);
  settings.refineSpp = 0;
  const SceneContent& content = *job.session->content;
  const gpu::DisplayCamera camera = jobCamera(job);
  gpu::RenderResult result;
  worker
      .submit(client,
              [&](gpu::VulkanContext&) { result = content.renderer->accumulate(camera.camera, settings, accumulator); })
      .get();
  return result;
}

gpu::RenderResult renderFrameJob(RenderWorker& worker, const std::string& client, const FrameJob& job,
                                 std::vector<float>* recycled) {
  const gpu::RenderSettings settings = jobSettings(job);
  const SceneContent& content = *job.session->content;
  if (content.quilt) {  // existing quilt content: interleaved for the display, nothing traced
    if (job.path == gpu::CameraPath::Quilt) {
      throw BadRequest("quilt", "scene '" + job.session->id + "' is already a quilt image; request its panel frames");
    }
    return content.quilt->frame(job.display->config);
  }
  const gpu::DisplayCamera camera = jobCamera(job);
  gpu::RenderResult result;
  worker
      .submit(client,
              [&](gpu::VulkanContext&) {
                if (recycled && !recycled->empty() && !job.cluster) content.renderer->recycle(std::move(*recycled));
                result = job.cluster ? job.cluster->render(job, camera, settings)
                                     : content.renderer->render(camera.camera, settings);
              })
      .get();
  return result;
}

}  // namespace ht::server
