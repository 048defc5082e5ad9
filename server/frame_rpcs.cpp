// frame_rpcs.cpp - RenderFrame, StreamFrames, Capture.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "frame_io/frame_file_names.h"
#include "frame_io/frame_package.h"
#include "server/capture_output.h"
#include "server/frame_encoding.h"
#include "server/frame_job.h"
#include "server/frame_sender.h"
#include "server/holotrace_service.h"
#include "server/panel_feed.h"
#include "server/path_rules.h"
#include "server/request_checks.h"
#include "server/status_mapping.h"

namespace ht::server {
namespace v1 = holotrace::v1;
namespace {

std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

v1::FrameHeader makeHeader(std::uint64_t frameId, const gpu::RenderResult& frame, const EncodedFrame& encoded,
                           v1::PixelFormat format, double queueMs) {
  v1::FrameHeader header;
  header.set_frame_id(frameId);
  header.set_width(encoded.width);
  header.set_height(encoded.height);
  header.set_format(format == v1::PIXEL_FORMAT_UNSPECIFIED ? v1::PIXEL_FORMAT_RGBA8 : format);
  header.set_views(encoded.views);
  header.set_render_ms(frame.totalMs);
  header.set_queue_ms(queueMs);
  for (const auto& stage : frame.stages) {
    auto* s = header.add_stages();
    s->set_name(stage.name);
    s->set_ms(stage.ms);
  }
  return header;
}

// Renders one frame and sends it; false when the client went away or stopped reading for longer than
// limits.stream_stall_seconds (`watch` cancels the blocked Write).
// `panel` (StreamRequest.present_on) also gets the frame, through its one-slot mailbox: never waits on the display.
bool renderAndSend(ServiceState& state, const std::string& client, const FrameJob& job, v1::PixelFormat format,
                   std::uint64_t dropped, grpc::ServerWriterInterface<v1::FramePart>& writer,
                   CallWatchdog::Watch& watch, present::PanelSink* panel = nullptr) {
  const auto queued = Clock::now();
  const gpu::RenderResult frame = renderFrameJob(state.worker, client, job);
  if (panel) panel->submit(panelFrameOf(frame, job));
  const double queueMs = std::max(0.0, msBetween(queued, Clock::now()) - frame.totalMs);
  const DisplayConfig display = displayForSession(job.display->config, *job.session);
  const EncodedFrame encoded = encodeFrame(frame, checkPixelFormat(format), {display, jobCamera(job).quilt});
  v1::FrameHeader header = makeHeader(state.nextFrameId++, frame, encoded, format, queueMs);
  header.set_dropped_frames(dropped);
  const CallWatchdog::Watch::Wait waiting(watch);
  return sendFrame(writer, std::move(header), encoded.bytes);
}

// Sleeps until `due` in short slices, so a cancelled call or a shutdown frees its slot within ~20 ms.
void waitForTick(ServiceState& state, grpc::ServerContext& context, Clock::time_point due) {
  while (Clock::now() < due && !context.IsCancelled()) {
    if (!state.sleepUntil(std::min(due, Clock::now() + std::chrono::milliseconds(20)))) return;
  }
}

frame_io::FrameFormat captureFormat(v1::CaptureFormat format) {
  switch (format) {
    case v1::CAPTURE_FORMAT_UNSPECIFIED:
    case v1::CAPTURE_FORMAT_PNG: return frame_io::FrameFormat::Png;
    case v1::CAPTURE_FORMAT_EXR: return frame_io::FrameFormat::Exr;
    default: throw BadRequest("format", "unknown capture format " + std::to_string(format));
  }
}

frame_io::ViewLayout captureLayout(v1::CaptureLayout layout) {
  switch (layout) {
    case v1::CAPTURE_LAYOUT_AUTO: return frame_io::ViewLayout::Auto;
    case v1::CAPTURE_LAYOUT_QUILT: return frame_io::ViewLayout::Quilt;
    case v1::CAPTURE_LAYOUT_VIEWS: return frame_io::ViewLayout::Views;
    default: throw BadRequest("layout", "unknown capture layout " + std::to_string(layout));
  }
}

// The files of one captured frame (proto CaptureLayout), packaged as `holotrace render` packages them.
std::vector<frame_io::FrameFile> captureFiles(const gpu::RenderResult& frame, const FrameJob& job,
                                              const std::string& stem, frame_io::FrameFormat format,
                                              frame_io::ViewLayout layout) {
  const DisplayConfig display = displayForSession(job.display->config, *job.session);
  const std::string name = stem + (format == frame_io::FrameFormat::Exr ? ".exr" : ".png");
  return frame_io::packageFrame({frame.width, frame.height, frame.views, frame.rgba}, {display, jobCamera(job).quilt},
                                layout, format, name)
      .files;
}

}  // namespace

grpc::Status HolotraceService::RenderFrame(grpc::ServerContext* context, const v1::RenderRequest* request,
                                           grpc::ServerWriter<v1::FramePart>* writer) {
  return guarded([&] {
    const FrameJob job = checkRenderRequest(state_, *request);
    StreamSlot slot(state_);
    CallWatchdog::Watch watch(state_.watchdog, *context, state_.config.limits.streamStallSeconds, "RenderFrame");
    if (!renderAndSend(state_, clientKey(*context), job, request->format(), 0, *writer, watch)) {
      throw ClientGone("client closed the stream");
    }
    return grpc::Status::OK;
  });
}

// Frames on a fixed clock (frame k due at start + k/fps). A frame is rendered only when the previous one has been
// written, so a slow client is never queued old frames: it gets the newest, and dropped_frames counts the ticks
// it missed (latest-frame-wins, docs/SERVICE.md §4 "Backpressure").
grpc::Status HolotraceService::StreamFrames(grpc::ServerContext* context, const v1::StreamRequest* request,
                                            grpc::ServerWriter<v1::FramePart>* writer) {
  return guarded([&] {
    // The range first: 1/fps of a tiny rate overflows the clock's 64-bit nanoseconds (and a NaN compares false).
    const double fps = request->frames_per_second();
    if (!(fps >= kMinFramesPerSecond && fps <= state_.config.limits.maxFramesPerSecond)) {
      throw BadRequest("frames_per_second", shortNumber(fps) + " is not in [" + shortNumber(kMinFramesPerSecond) +
                                                ", " + shortNumber(state_.config.limits.maxFramesPerSecond) +
                                                "] (limits.max_frames_per_second)");
    }
    FrameJob job = checkRenderRequest(state_, request->render());
    std::shared_ptr<present::PanelSink> panel;
    if (!request->present_on().empty()) panel = streamPanelSink(state_, request->present_on(), job);
    StreamSlot slot(state_);
    const SceneLibrary::Pin pin(state_.scenes, request->render().scene_id());  // not idled out between slow frames
    CallWatchdog::Watch watch(state_.watchdog, *context, state_.config.limits.streamStallSeconds, "StreamFrames");
    const std::string client = clientKey(*context);
    // <= 1000 s after the check above, >= 1 ms (limits.max_frames_per_second <= 1000): no overflow, never zero.
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / fps));
    const auto start = Clock::now();
    std::uint64_t tick = 0, dropped = 0;
    while (!context->IsCancelled()) {
      if (state_.shuttingDown) throw ShuttingDown("holotraced is shutting down");
      job.session = state_.scenes.find(request->render().scene_id());  // picks up UpdateScene
      job.seed = request->render().seed() + static_cast<std::uint32_t>(tick);
      if (!renderAndSend(state_, client, job, request->render().format(), dropped, *writer, watch, panel.get())) break;
      const auto now = Clock::now();
      const auto due = static_cast<std::uint64_t>((now - start) / period) + 1;  // next tick not yet passed
      dropped = due > tick + 1 ? due - tick - 1 : 0;
      tick = std::max(tick + 1, due);
      waitForTick(state_, *context, start + period * static_cast<Clock::rep>(tick));
    }
    return grpc::Status(grpc::StatusCode::CANCELLED, "client cancelled the stream");
  });
}

grpc::Status HolotraceService::Capture(grpc::ServerContext* context, const v1::CaptureRequest* request,
                                       grpc::ServerWriter<v1::CaptureProgress>* writer) {
  return guarded([&] {
    checkFileNameComponent("name", request->name());
    const std::uint32_t frames = request->frames() == 0 ? 1 : request->frames();
    if (frames > state_.config.limits.maxCaptureFrames) {
      throw LimitExceeded("frames = " + std::to_string(frames) + " (limits.max_capture_frames = " +
                          std::to_string(state_.config.limits.maxCaptureFrames) + ")");
    }
    const frame_io::FrameFormat format = captureFormat(request->format());
    const frame_io::ViewLayout layout = captureLayout(request->layout());
    FrameJob job = checkRenderRequest(state_, request->render());
    const gpu::DisplayCamera camera = jobCamera(job);
    if (!frame_io::layoutAllowed({job.display->config, camera.quilt}, camera.shape.views, layout)) {
      throw BadRequest("layout",
                       "the views of display '" + job.display->id + "' do not form a quilt; use CAPTURE_LAYOUT_VIEWS");
    }
    StreamSlot slot(state_);
    const SceneLibrary::Pin pin(state_.scenes, request->render().scene_id());
    CallWatchdog::Watch watch(state_.watchdog, *context, state_.config.limits.streamStallSeconds, "Capture");
    CaptureOutput output(state_.outputSink, request->name(), request->overwrite());  // the name is ours till the end
    const std::string client = clientKey(*context);
    const auto checkGoing = [&](std::uint32_t done) {  // before a render, and before writing what was rendered
      if (context->IsCancelled())
        throw ClientGone("capture cancelled after " + std::to_string(done) + " complete frames");
      if (state_.shuttingDown) throw ShuttingDown("shutting down after " + std::to_string(done) + " complete frames");
    };
    for (std::uint32_t i = 0; i < frames; ++i) {
      checkGoing(i);
      job.seed = request->render().seed() + i;
      const gpu::RenderResult frame = renderFrameJob(state_.worker, client, job);
      const std::vector<frame_io::FrameFile> files =
          captureFiles(frame, job, frame_io::captureFrameStem(request->name(), i), format, layout);
      checkGoing(i);             // no file after a cancel
      output.writeFrame(files);  // the frame's files whole or not at all
      for (const frame_io::FrameFile& file : files) {
        v1::CaptureProgress progress;
        progress.set_frames_done(i + 1);
        progress.set_frames_total(frames);
        progress.set_file(file.name);
        const CallWatchdog::Watch::Wait waiting(watch);
        writer->Write(progress);  // a gone or stalled client is noticed at the next frame (IsCancelled)
      }
    }
    return grpc::Status::OK;
  });
}

}  // namespace ht::server
