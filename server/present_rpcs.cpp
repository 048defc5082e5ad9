// present_rpcs.cpp - Present (frames onto a panel through the daemon's display sink) and the panel part of Status
// (docs/SERVICE.md §11).
#include <chrono>

#include "present/panel_frame.h"
#include "server/frame_job.h"
#include "server/holotrace_service.h"
#include "server/panel_feed.h"
#include "server/panel_sinks.h"
#include "server/present_status.h"
#include "server/request_checks.h"
#include "server/status_mapping.h"

namespace ht::server {
namespace v1 = holotrace::v1;
namespace {

using Clock = std::chrono::steady_clock;

// Shared: a sink removed by SIGHUP meanwhile stays alive until this call ends.
std::shared_ptr<present::PanelSink> sinkFor(const ServiceState& state, const std::string& displayId) {
  std::shared_ptr<present::PanelSink> sink = state.panels ? state.panels->find(displayId) : nullptr;
  if (!sink) {
    throw BadRequest("render.display_id",
                     "display '" + displayId + "' has no panel sink; list it in the daemon config's \"present\"");
  }
  return sink;
}

std::uint32_t checkedFrameCount(const ServiceState& state, const v1::PresentRequest& request) {
  const std::uint32_t frames = std::max<std::uint32_t>(1, request.frames());
  if (frames > state.config.limits.maxCaptureFrames) {
    throw LimitExceeded("frames = " + std::to_string(frames) +
                        " (limits.max_capture_frames = " + std::to_string(state.config.limits.maxCaptureFrames) + ")");
  }
  const double fps = request.frames_per_second();
  if (fps < 0.0 || fps > state.config.limits.maxFramesPerSecond || fps != fps) {
    throw BadRequest("frames_per_second", "must be in [0, " + std::to_string(state.config.limits.maxFramesPerSecond) +
                                              "] (0 = as fast as frames render)");
  }
  return frames;
}

}  // namespace

grpc::Status HolotraceService::Present(grpc::ServerContext* context, const v1::PresentRequest* request,
                                       grpc::ServerWriter<v1::PresentProgress>* writer) {
  return guarded([&] {
    const std::uint32_t frames = checkedFrameCount(state_, *request);
    FrameJob job = checkRenderRequest(state_, request->render());
    const std::shared_ptr<present::PanelSink> sink = sinkFor(state_, job.display->id);
    StreamSlot slot(state_);
    const std::string client = clientKey(*context);
    const auto start = Clock::now();
    const double fps = request->frames_per_second();
    std::vector<float> recycled;  // the last frame's pixels, for the next to be written into (renderFrameJob)
    for (std::uint32_t i = 0; i < frames; ++i) {
      if (context->IsCancelled()) throw ClientGone("present cancelled after " + std::to_string(i) + " frames");
      if (state_.shuttingDown) throw ShuttingDown("shutting down after " + std::to_string(i) + " frames");
      if (fps > 0.0 && i > 0 &&
          !state_.sleepUntil(start +
                             std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(i / fps)))) {
        throw ShuttingDown("shutting down after " + std::to_string(i) + " frames");
      }
      job.session = state_.scenes.find(request->render().scene_id());  // picks up UpdateScene
      job.seed = request->render().seed() + i;
      gpu::RenderResult frame = renderFrameJob(state_.worker, client, job, &recycled);
      sink->submit(panelFrameOf(frame, job));
      recycled = std::move(frame.rgba);  // the panel frame is a copy
      v1::PresentProgress progress;
      progress.set_frame_id(state_.nextFrameId++);
      progress.set_frames_done(i + 1);
      progress.set_frames_total(frames);
      progress.set_render_ms(frame.totalMs);
      fillPanelStatus(job.display->id, sink->stats(), state_.panels->xDisplay(), *progress.mutable_panel());
      writer->Write(progress);  // a gone client is noticed at the next frame (IsCancelled)
    }
    return grpc::Status::OK;
  });
}

}  // namespace ht::server
